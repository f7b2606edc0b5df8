#pragma once
/// \file pose_covariance.h GASP's pose uncertainty in MRPT's terms. GASP's information matrices
/// are over the left perturbation T <- Exp(xi) T, xi = [t; omega] ([m], [rad]) in the frame the
/// pose maps into (registration_result.h); MRPT's CPose3DPDFGaussian has its covariance over
/// [x y z yaw pitch roll]. The conversion is first order: cov_ypr = J I^-1 J^T with
/// J = d[x y z yaw pitch roll](Exp(xi) T) / d xi at xi = 0.
#include <mrpt/poses/CPose3DPDFGaussian.h>

#include <optional>

#include "gasp/core/pose.h"
#include "gasp/core/pose_perturbation.h"  // Matrix6, adjoint(): Exp(Ad_S xi) = S Exp(xi) S^-1

namespace gasp {

/// The information of T_a_b = S_a T_ca_cb S_b^-1 (left perturbation in a) from the information of
/// T_ca_cb (left perturbation in ca): I_a = Ad(S_a^-1)^T I_ca Ad(S_a^-1).
Matrix6 informationInFrame(const Matrix6& information_ca, const Isometry3& S_a);

/// J = d[x y z yaw pitch roll](Exp(xi) T) / d xi at xi = 0 (central differences, angles wrapped).
Matrix6 yprJacobian(const Isometry3& T);

/// T with covariance J I^-1 J^T, or nullopt when the information is not symmetric positive
/// definite (some direction unobservable: no covariance can be claimed).
std::optional<mrpt::poses::CPose3DPDFGaussian> poseWithInformation(const Isometry3& T, const Matrix6& information);

/// T with covariance J C J^T, C over the left perturbation [t r] (the marginals of a pose graph,
/// gasp/slam/pose_graph_marginals.h). Throws gasp::Error when C is not finite or not symmetric,
/// or when the result is not finite (pitch at +-90 deg, where yaw and roll are not defined).
mrpt::poses::CPose3DPDFGaussian poseWithCovariance(const Isometry3& T, const Matrix6& covariance);

}  // namespace gasp
