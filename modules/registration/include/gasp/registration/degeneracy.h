#pragma once
/// \file degeneracy.h Which pose directions an information matrix leaves unobservable.
///
/// The information I is 6x6 over the left perturbation xi = [rho; omega] of T_target_source,
/// T <- Exp(xi) T, in the target frame: rho a translation [m], omega a rotation [rad] about the
/// target frame's origin (see refinement.h). To compare translations with rotations and to make
/// the verdict independent of where the camera is, the check uses the conditioned information
///   I_c = S^T B^T I B S,   B = [I3 [c]x; 0 I3],   S = diag(I3, I3 / L)
/// i.e. rotations about the scene centre c and expressed as arc lengths [m] at the scene radius
/// L (the RMS distance of the residuals' points from c, at least kMinSceneRadiusM). A unit
/// eigenvector v of I_c with eigenvalue lambda is unobservable when
///   lambda < min_eigenvalue_ratio * lambda_max   or   lambda < 1 / max_std_m^2,
/// the second saying the pose's standard deviation along v would exceed max_std_m.
#include <Eigen/Core>

#include <string>

namespace gasp {

using Matrix6d = Eigen::Matrix<double, 6, 6>;
using Vector6d = Eigen::Matrix<double, 6, 1>;

inline constexpr double kMinSceneRadiusM = 0.1;  ///< floor of the scene radius L [m]

struct DegeneracyParams {
  double min_eigenvalue_ratio = 1e-2;  ///< lambda / lambda_max below this: unobservable
  double max_std_m = 0.05;             ///< lambda < 1 / max_std_m^2 [1/m^2]: unobservable
};

/// Throws gasp::Error naming the first invalid parameter.
void validate(const DegeneracyParams& params);

struct DegeneracyAnalysis {
  bool degenerate = false;
  Vector6d eigenvalues = Vector6d::Zero();  ///< of I_c, ascending [1/m^2]
  /// Unit columns in I_c's coordinates [translation [m]; rotation as arc length at L [m]], a basis
  /// of the unobservable subspace, translation-like directions first.
  Eigen::Matrix<double, 6, Eigen::Dynamic> unobservable_directions;
  /// The same directions as left perturbations [t r] of the pose (rotations about the origin in
  /// radians), B S times each column: what another analysis can take over.
  Eigen::Matrix<double, 6, Eigen::Dynamic> unobservable_twists;
  /// "translation along (x, y, z); rotation about (x, y, z)" (directions in the target frame,
  /// rotations about axes through c); empty when nothing is unobservable.
  std::string reason;
};

/// B S (above): maps conditioned coordinates [rho_c; arc] to the left perturbation [rho; omega].
Matrix6d conditioning(const Eigen::Vector3d& centre, double radius_m);

/// I_c from I (above).
Matrix6d conditionedInformation(const Matrix6d& information, const Eigen::Vector3d& centre, double radius_m);

/// "translation along (x, y, z); rotation about (x, y, z)" for unit columns in I_c's coordinates.
std::string directionsText(const Eigen::Matrix<double, 6, Eigen::Dynamic>& conditioned_directions);

/// The eigen-decomposition of I_c and the verdict.
DegeneracyAnalysis analyseDegeneracy(const Matrix6d& information, const Eigen::Vector3d& centre, double radius_m,
                                     const DegeneracyParams& params = {});

}  // namespace gasp
