#pragma once
/// \file registration_result.h What a pose estimate claims and how well it is supported.
#include <Eigen/Core>

#include <optional>
#include <string>
#include <vector>

#include "gasp/core/pose.h"
#include "gasp/registration/degeneracy.h"

namespace gasp {

struct RegistrationResult {
  bool success = false;     ///< a pose is claimed: solved, enough inliers and not degenerate
  bool degenerate = false;  ///< some direction is unobservable (degeneracy.h); success is then false
  /// A partial pose is claimed (partial_pose.h): degenerate, success false, and T_target_source
  /// holds in the observed directions only; unobservable_directions are free (the information
  /// must be used with them zeroed: observedInformation()).
  bool partial = false;
  bool estimated() const { return success || partial; }  ///< a full or a partial pose is claimed
  Isometry3 T_target_source = Isometry3::Identity();  ///< the estimate (also when not claimed)

  std::vector<int> inliers;  ///< correspondences the final estimate rests on (ascending indices)
  int num_inliers = 0;       ///< inliers.size()
  int num_residuals = 0;     ///< point-to-plane terms in the final problem (patch + dense)
  double rms_residual_m = 0.0;     ///< RMS of the final point-to-plane residuals [m], unweighted
  double median_residual_m = 0.0;  ///< median of their magnitudes [m]
  int iterations = 0;              ///< Ceres iterations, summed over refinement rounds
  int ransac_iterations = 0;       ///< RANSAC samples drawn (estimatePose only)

  /// J^T W J / sigma^2 at the estimate: order [tx ty tz rx ry rz] of the left perturbation
  /// T <- Exp(xi) T in the target frame (rotation about the target origin, radians), W the
  /// term weights times the robust loss's rho' (refinement.h) [1/m^2, 1/(m rad), 1/rad^2].
  Matrix6d information = Matrix6d::Zero();
  /// Eigenvalues of the conditioned information (degeneracy.h), ascending [1/m^2].
  Vector6d information_eigenvalues = Vector6d::Zero();
  /// When degenerate: a basis of the unobservable directions, in the conditioned coordinates.
  Eigen::Matrix<double, 6, Eigen::Dynamic> unobservable_directions;
  Eigen::Vector3d scene_centre = Eigen::Vector3d::Zero();  ///< c of the conditioning, target frame [m]
  double scene_radius_m = 0.0;                             ///< L of the conditioning [m]

  /// RANSAC's best distinct alternative (ransac.h; estimatePose only, as RANSAC left it), and its
  /// inliers (ascending indices into the correspondences).
  std::optional<Isometry3> alternative_T_target_source;
  std::vector<int> alternative_inliers;

  double ransac_ms = 0.0;  ///< wall time of RANSAC (estimatePose only)
  double refine_ms = 0.0;  ///< wall time of refinement / evaluation
  std::string reason;      ///< why no pose is claimed, or why degenerate
};

}  // namespace gasp
