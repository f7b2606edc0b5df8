#include "pose_graph_problem.h"

#include "gasp/slam/pose_graph.h"
#include "edge_residual.h"

namespace gasp::detail {

PoseGraphProblem::PoseGraphProblem(const std::vector<Isometry3>& T_world_node, const std::vector<PoseConstraint>& edges)
    : manifold_(std::make_unique<ceres::EigenQuaternionManifold>()) {
  checkPoseGraph(T_world_node, edges);
  const std::size_t n = T_world_node.size();
  q_.resize(n);  // sized once: the problem holds pointers into them
  t_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    q_[i] = Eigen::Quaterniond(T_world_node[i].rotation()).normalized();
    t_[i] = T_world_node[i].translation();
  }
  used_.assign(n, false);
  roots_ = pieceRoots(n, edges);
  ceres::Problem::Options options;
  options.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  problem_ = std::make_unique<ceres::Problem>(options);
  costs_.reserve(edges.size());
  for (const PoseConstraint& c : edges) {
    costs_.push_back(std::make_unique<ceres::AutoDiffCostFunction<EdgeResidual, 6, 4, 3, 4, 3>>(
        new EdgeResidual(c.T_from_to, sqrtInformation(c))));  // the cost function owns its functor
    problem_->AddResidualBlock(costs_.back().get(), nullptr, q(c.from), t(c.from), q(c.to), t(c.to));
    for (const std::size_t i : {c.from, c.to}) {
      if (!used_[i]) problem_->SetManifold(q(i), manifold_.get());
      used_[i] = true;
    }
  }
  for (std::size_t i = 0; i < n; ++i)
    if (fixed(i)) {
      problem_->SetParameterBlockConstant(q(i));
      problem_->SetParameterBlockConstant(t(i));
    }
}

Isometry3 PoseGraphProblem::pose(std::size_t i) const {
  Isometry3 T = Isometry3::Identity();
  T.linear() = q_[i].normalized().toRotationMatrix();
  T.translation() = t_[i];
  return T;
}

}  // namespace gasp::detail
