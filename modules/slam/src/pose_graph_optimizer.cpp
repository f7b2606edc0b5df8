#include "gasp/slam/pose_graph_optimizer.h"

#include <ceres/ceres.h>

#include <string>

#include "gasp/core/error.h"
#include "gasp/slam/pose_graph.h"
#include "pose_graph_problem.h"

namespace gasp {

namespace {

using detail::PoseGraphProblem;

double totalChi2(const std::vector<Isometry3>& T, const std::vector<PoseConstraint>& edges) {
  double s = 0.0;
  for (const PoseConstraint& c : edges) s += edgeChi2(T[c.from], T[c.to], c);
  return s;
}

}  // namespace

void validate(const PoseGraphSettings& settings) {
  if (settings.max_iterations < 1 || settings.num_threads < 1 || !(settings.function_tolerance > 0.0))
    throw Error("pose graph: max_iterations, num_threads and function_tolerance must be positive");
}

PoseGraphResult optimizePoseGraph(const std::vector<Isometry3>& T_world_node, const std::vector<PoseConstraint>& edges,
                                  const PoseGraphSettings& settings) {
  const std::size_t n = T_world_node.size();
  validate(settings);
  PoseGraphProblem graph(T_world_node, edges);  // checks the graph before the chi-square reads it

  PoseGraphResult out;
  out.T_world_node = T_world_node;
  out.initial_chi2 = totalChi2(T_world_node, edges);
  for (std::size_t i = 0; i < n; ++i) out.fixed_nodes += graph.fixed(i) ? 1 : 0;
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
  ceres::Solve(options, &graph.problem(), &summary);
  out.converged = summary.termination_type == ceres::CONVERGENCE;
  out.iterations = static_cast<int>(summary.iterations.size());
  out.message = summary.BriefReport();
  for (std::size_t i = 0; i < n; ++i)
    if (graph.used(i)) out.T_world_node[i] = graph.pose(i);
  out.final_chi2 = totalChi2(out.T_world_node, edges);
  return out;
}

}  // namespace gasp
