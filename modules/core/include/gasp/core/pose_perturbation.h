#pragma once
/// \file pose_perturbation.h Small rigid motions as 6-vectors, in GASP's convention for pose
/// uncertainty (registration_result.h, pose_constraint.h): xi = [t r] acts on the left,
/// T = Exp(xi) T_hat, in the frame T maps into, with Exp(xi) = [AngleAxis(r), t].
#include <Eigen/Core>

#include "gasp/core/pose.h"

namespace gasp {

using Vector6 = Eigen::Matrix<double, 6, 1>;
using Matrix6 = Eigen::Matrix<double, 6, 6>;

/// [v]x: skew(v) * w = v.cross(w).
Eigen::Matrix3d skew(const Eigen::Vector3d& v);

/// Exp(xi) = [AngleAxis(r), t] for xi = [t r].
Isometry3 expLeft(const Vector6& xi);

/// xi with T_a = Exp(xi) T_b: [translation of T_a T_b^-1, angle-axis of its rotation]. (The NEES
/// of gasp::eval uses the exact SE(3) logarithm instead; the two agree to first order.)
Vector6 leftPerturbation(const Isometry3& T_a, const Isometry3& T_b);

/// Ad(T) for the [t r] left perturbation: T Exp(xi) T^-1 = Exp(Ad(T) xi) to first order;
/// Ad = [R, [t]x R; 0, R].
Matrix6 adjoint(const Isometry3& T);

}  // namespace gasp
