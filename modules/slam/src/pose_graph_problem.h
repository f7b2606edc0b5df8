#pragma once
// Private to gasp::slam: the pose graph as a Ceres problem, built one way for the optimiser
// (pose_graph_optimizer.cpp) and the marginals (pose_graph_marginals.cpp).
#include <ceres/ceres.h>
#include <Eigen/Geometry>

#include <cstddef>
#include <memory>
#include <vector>

#include "gasp/core/pose.h"
#include "gasp/odometry/pose_constraint.h"

namespace gasp::detail {

/// One unit quaternion (Eigen's x y z w, on EigenQuaternionManifold) and one translation per
/// node, one EdgeResidual (edge_residual.h) per constraint; the lowest-index node of each
/// connected piece held constant (the gauge). Nodes no edge touches are not in the problem.
class PoseGraphProblem {
 public:
  /// Throws gasp::Error for the graphs checkPoseGraph() and sqrtInformation() refuse.
  PoseGraphProblem(const std::vector<Isometry3>& T_world_node, const std::vector<PoseConstraint>& edges);
  PoseGraphProblem(const PoseGraphProblem&) = delete;
  PoseGraphProblem& operator=(const PoseGraphProblem&) = delete;

  ceres::Problem& problem() { return *problem_; }
  bool used(std::size_t i) const { return used_[i]; }            ///< some edge touches node i
  bool fixed(std::size_t i) const { return used_[i] && roots_[i] == i; }  ///< a piece's root
  const std::vector<std::size_t>& roots() const { return roots_; }  ///< pieceRoots() of the graph
  double* q(std::size_t i) { return q_[i].coeffs().data(); }
  double* t(std::size_t i) { return t_[i].data(); }
  const Eigen::Quaterniond& quaternion(std::size_t i) const { return q_[i]; }
  const Eigen::Vector3d& translation(std::size_t i) const { return t_[i]; }
  /// Node i's pose as the parameters hold it now.
  Isometry3 pose(std::size_t i) const;

 private:
  std::vector<Eigen::Quaterniond> q_;
  std::vector<Eigen::Vector3d> t_;
  std::vector<bool> used_;
  std::vector<std::size_t> roots_;
  // The problem borrows the costs and the manifold; declared last, so it goes first.
  std::unique_ptr<ceres::EigenQuaternionManifold> manifold_;
  std::vector<std::unique_ptr<ceres::CostFunction>> costs_;
  std::unique_ptr<ceres::Problem> problem_;
};

}  // namespace gasp::detail
