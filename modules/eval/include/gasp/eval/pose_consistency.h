#pragma once
/// \file pose_consistency.h Is a pose's information matrix consistent with its actual error?
///
/// An estimate T_est with information I claims that its error xi, defined by T_est = Exp(xi) T_ref
/// (the left perturbation of registration_result.h: xi = [rho; omega], rho [m], omega [rad] in the
/// target frame), is distributed as N(0, I^-1). Then the normalised estimation error squared
/// NEES = xi^T I xi follows a chi-square distribution with 6 degrees of freedom: mean 6, median
/// 5.35, 95 % below 12.59 (Bar-Shalom, Li, Kirubarajan, "Estimation with Applications to Tracking
/// and Navigation", 5.4.2). A NEES far above that says the information is optimistic: over a set
/// of estimates, median NEES / 5.35 estimates the factor by which it overstates the certainty.
#include <Eigen/Core>

#include "gasp/core/pose.h"

namespace gasp::eval {

using Vector6 = Eigen::Matrix<double, 6, 1>;
using Matrix6 = Eigen::Matrix<double, 6, 6>;

/// Median of the chi-square distribution with 6 degrees of freedom.
inline constexpr double kChiSquare6Median = 5.348120627;
/// Its 95 % quantile.
inline constexpr double kChiSquare6Quantile95 = 12.591587243;
/// Median of the chi-square distribution with 3 degrees of freedom (the marginal NEES below).
inline constexpr double kChiSquare3Median = 2.365973884;

/// xi = Log(T_est T_ref^-1) as [rho; omega]: the exact SE(3) logarithm, so Exp(xi) T_ref = T_est
/// (rho = V(omega)^-1 t with V the left Jacobian of SO(3)).
Vector6 leftPerturbation(const Isometry3& T_est, const Isometry3& T_ref);

/// xi^T I xi for xi = leftPerturbation(T_est, T_ref). Throws gasp::Error when the information is
/// not finite or not symmetric positive semi-definite (within 1e-9 relative).
double nees(const Isometry3& T_est, const Isometry3& T_ref, const Matrix6& information);

/// The NEES and its translation and rotation parts: rho^T C_tt^-1 rho and omega^T C_rr^-1 omega
/// with C = information^-1 (each chi-square with 3 degrees of freedom if the information were
/// right), which tell which part of a claimed certainty the errors contradict.
struct NeesParts {
  double all = 0.0, translation = 0.0, rotation = 0.0;
};

/// As nees(), and the parts; throws gasp::Error also when the information is not invertible.
NeesParts neesParts(const Isometry3& T_est, const Isometry3& T_ref, const Matrix6& information);

}  // namespace gasp::eval
