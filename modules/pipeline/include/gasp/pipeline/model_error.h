#pragma once
/// \file model_error.h The information a pose graph should get for a pair's pose.
///
/// The refinement's information (refinement.h: J^T W J / sigma^2 over thousands of point-to-plane
/// terms) is the right shape but far too certain for real data: it treats every term as an
/// independent measurement, while what limits a real pose is shared by all terms -- the depth
/// camera's calibration and rolling shutter, the segmentation, the timing, so on real pairs the
/// error's NEES (pose_consistency.h) is far beyond what that information allows
/// (docs/pipeline.md, "How far the information can be trusted"). The model error adds that part
/// as an isotropic covariance in the information's coordinates (the left perturbation
/// xi = [rho; omega] in the target frame, registration_result.h):
///
///   C_edge = I^-1 + diag(s_t^2, s_t^2, s_t^2, s_r^2, s_r^2, s_r^2),   I_edge = C_edge^-1.
///
/// With both sigmas 0, I_edge = I.
#include <Eigen/Core>

namespace gasp {

struct ModelError {
  double sigma_t_m = 0.01;     ///< s_t, per axis [m]
  double sigma_r_deg = 0.75;   ///< s_r, per axis, rotation about the target camera's origin [deg]
};

/// Throws gasp::Error unless both sigmas are finite and >= 0.
void validate(const ModelError& e);

/// diag(s_t^2, s_t^2, s_t^2, s_r^2, s_r^2, s_r^2) [m^2, rad^2] (validate()s e).
Eigen::Matrix<double, 6, 6> modelErrorCovariance(const ModelError& e);

/// I_edge above. Throws gasp::Error when the information is not finite or not positive definite
/// (a claimed pose's always is).
Eigen::Matrix<double, 6, 6> informationWithModelError(const Eigen::Matrix<double, 6, 6>& information,
                                                      const ModelError& e);

}  // namespace gasp
