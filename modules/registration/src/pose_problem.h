#pragma once
// Internal: the Ceres problem behind refinement.h -- point-to-plane terms on T_target_source
// parametrised as an Eigen quaternion (EigenQuaternionManifold) and a translation.
#include <ceres/ceres.h>

#include <array>
#include <memory>
#include <vector>

#include "gasp/registration/correspondence.h"
#include "gasp/registration/refinement.h"

namespace gasp::detail {

class PoseProblem {
 public:
  PoseProblem(const Isometry3& T_init, const RefinementParams& params);

  void addPatch(const PatchCorrespondence& c);  ///< forward term, and backward if bidirectional
  void addDense(const PointToPlane& term);
  int numResiduals() const { return static_cast<int>(points_.size()); }

  ceres::Solver::Summary solve();
  Isometry3 pose() const;
  void setPose(const Isometry3& T);  ///< moves the parameters (no solve)
  /// Residuals [m] at the current pose, without weights or robust loss.
  std::vector<double> residuals();
  /// J^T J / sigma^2 over xi = [rho; omega] (refinement.h), robustified and weighted.
  Matrix6d information();
  /// Weighted centroid and RMS radius [m] of the terms' points in the target frame.
  void sceneExtent(Eigen::Vector3d& centre, double& radius_m) const;

 private:
  struct TermPoint {
    Eigen::Vector3d point;  // in the source frame when mapped, else the target frame
    bool mapped;            // true: the point is T * point in the target frame
    double weight;
  };
  void add(std::unique_ptr<ceres::CostFunction> cost, double weight, const TermPoint& where);

  RefinementParams params_;
  std::array<double, 4> q_{};  // Eigen order x, y, z, w
  std::array<double, 3> t_{};
  std::vector<TermPoint> points_;
  // Owned here; the problem below only borrows them (and is destroyed first).
  std::unique_ptr<ceres::LossFunction> loss_;
  std::vector<std::unique_ptr<ceres::LossFunction>> scaled_losses_;
  std::vector<std::unique_ptr<ceres::CostFunction>> costs_;
  std::unique_ptr<ceres::Manifold> quaternion_manifold_;
  ceres::Problem problem_;
};

}  // namespace gasp::detail
