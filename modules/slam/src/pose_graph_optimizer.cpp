#include "gasp/slam/pose_graph_optimizer.h"

#include <ceres/ceres.h>

#include <memory>
#include <string>

#include "gasp/core/error.h"
#include "gasp/slam/pose_graph.h"
#include "edge_residual.h"

namespace gasp {

namespace {

using detail::EdgeResidual;
using detail::sqrtInformation;

double totalChi2(const std::vector<Isometry3>& T, const std::vector<PoseConstraint>& edges) {
  double s = 0.0;
  for (const PoseConstraint& c : edges) s += edgeChi2(T[c.from], T[c.to], c);
  return s;
}

}  // namespace

PoseGraphResult optimizePoseGraph(const std::vector<Isometry3>& T_world_node, const std::vector<PoseConstraint>& edges,
                                  const PoseGraphSettings& settings) {
  const std::size_t n = T_world_node.size();
  detail::checkPoseGraph(T_world_node, edges);
  if (settings.max_iterations < 1 || settings.num_threads < 1 || !(settings.function_tolerance > 0.0))
    throw Error("pose graph: max_iterations, num_threads and function_tolerance must be positive");

  PoseGraphResult out;
  out.T_world_node = T_world_node;
  out.initial_chi2 = totalChi2(T_world_node, edges);

  // Parameters: unit quaternion (x y z w, Eigen's order) and translation per node.
  std::vector<Eigen::Quaterniond> q(n);
  std::vector<Eigen::Vector3d> t(n);
  for (std::size_t i = 0; i < n; ++i) {
    q[i] = Eigen::Quaterniond(T_world_node[i].rotation()).normalized();
    t[i] = T_world_node[i].translation();
  }
  // The problem borrows the costs and the manifold (owned here), as in the registration's PoseProblem.
  // Declared before the problem, so they outlive it.
  const auto manifold = std::make_unique<ceres::EigenQuaternionManifold>();
  std::vector<std::unique_ptr<ceres::CostFunction>> costs;
  costs.reserve(edges.size());
  ceres::Problem::Options problem_options;
  problem_options.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  problem_options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(problem_options);
  std::vector<bool> used(n, false);
  for (const PoseConstraint& c : edges) {
    costs.push_back(std::make_unique<ceres::AutoDiffCostFunction<EdgeResidual, 6, 4, 3, 4, 3>>(
        new EdgeResidual(c.T_from_to, sqrtInformation(c))));  // the cost function owns its functor
    problem.AddResidualBlock(costs.back().get(), nullptr, q[c.from].coeffs().data(), t[c.from].data(),
                             q[c.to].coeffs().data(), t[c.to].data());
    for (const std::size_t i : {c.from, c.to}) {
      if (!used[i]) problem.SetManifold(q[i].coeffs().data(), manifold.get());
      used[i] = true;
    }
  }
  const std::vector<std::size_t> roots = pieceRoots(n, edges);
  for (std::size_t i = 0; i < n; ++i)
    if (used[i] && roots[i] == i) {
      problem.SetParameterBlockConstant(q[i].coeffs().data());
      problem.SetParameterBlockConstant(t[i].data());
      ++out.fixed_nodes;
    }
  if (edges.empty()) {
    out.converged = true;
    out.message = "no constraints";
    return out;
  }

  ceres::Solver::Options options;
  if (ceres::IsSparseLinearAlgebraLibraryTypeAvailable(ceres::SUITE_SPARSE)) {
    options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
    options.sparse_linear_algebra_library_type = ceres::SUITE_SPARSE;
  } else if (ceres::IsSparseLinearAlgebraLibraryTypeAvailable(ceres::EIGEN_SPARSE)) {
    options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
    options.sparse_linear_algebra_library_type = ceres::EIGEN_SPARSE;
  } else {
    options.linear_solver_type = ceres::DENSE_QR;
  }
  options.max_num_iterations = settings.max_iterations;
  options.function_tolerance = settings.function_tolerance;
  options.num_threads = settings.num_threads;
  options.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  out.converged = summary.termination_type == ceres::CONVERGENCE;
  out.iterations = static_cast<int>(summary.iterations.size());
  out.message = summary.BriefReport();
  for (std::size_t i = 0; i < n; ++i) {
    if (!used[i]) continue;
    Isometry3 T = Isometry3::Identity();
    T.linear() = q[i].normalized().toRotationMatrix();
    T.translation() = t[i];
    out.T_world_node[i] = T;
  }
  out.final_chi2 = totalChi2(out.T_world_node, edges);
  return out;
}

}  // namespace gasp
