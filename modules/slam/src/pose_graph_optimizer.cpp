#include "gasp/slam/pose_graph_optimizer.h"

#include <ceres/ceres.h>

#include <string>
#include <utility>
#include <vector>

#include "gasp/core/error.h"
#include "gasp/slam/pose_graph.h"
#include "edge_residual.h"
#include "pose_graph_problem.h"

namespace gasp {

namespace {

using detail::checkPoseGraph;
using detail::PoseGraphProblem;
using detail::sqrtInformation;

double totalChi2(const std::vector<Isometry3>& T, const std::vector<PoseConstraint>& edges) {
  double s = 0.0;
  for (const PoseConstraint& c : edges) s += edgeChi2(T[c.from], T[c.to], c);
  return s;
}

/// The leaves, peeled: a node other than its piece's root with one edge left, then the nodes that
/// leaves one edge, and so on. Each with the edge it hangs by, in the order peeled; `kept[e]` is
/// false for those edges.
std::vector<std::pair<std::size_t, std::size_t>> peelLeaves(std::size_t n, const std::vector<PoseConstraint>& edges,
                                                            std::vector<bool>& kept) {
  const std::vector<std::size_t> roots = pieceRoots(n, edges);
  std::vector<std::size_t> degree(n, 0);
  std::vector<std::vector<std::size_t>> incident(n);
  for (std::size_t e = 0; e < edges.size(); ++e)
    for (const std::size_t i : {edges[e].from, edges[e].to}) {
      ++degree[i];
      incident[i].push_back(e);
    }
  kept.assign(edges.size(), true);
  std::vector<std::pair<std::size_t, std::size_t>> peeled;
  std::vector<std::size_t> leaves;
  for (std::size_t i = 0; i < n; ++i)
    if (degree[i] == 1 && roots[i] != i) leaves.push_back(i);
  while (!leaves.empty()) {
    const std::size_t i = leaves.back();
    leaves.pop_back();
    if (degree[i] != 1) continue;
    std::size_t e = 0;
    for (const std::size_t candidate : incident[i])
      if (kept[candidate]) e = candidate;
    kept[e] = false;
    peeled.emplace_back(i, e);
    const std::size_t other = edges[e].from == i ? edges[e].to : edges[e].from;
    --degree[i];
    if (--degree[other] == 1 && roots[other] != other) leaves.push_back(other);
  }
  return peeled;
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
  checkPoseGraph(T_world_node, edges);  // before the chi-square and the peeling read it
  for (const PoseConstraint& c : edges) sqrtInformation(c);  // throws for one not positive definite
  // A node other than its piece's root that hangs by one edge is, at the optimum, where that edge
  // puts it: its residual is then zero whatever the rest, and it pulls on nothing. So the leaves
  // (and the branches they end) are peeled off, the rest is optimised, and they are placed after:
  // the same optimum, with the unknowns of the graph's core only (an odometry's frames between
  // keyframes hang by their one constraint).
  std::vector<bool> kept;
  const std::vector<std::pair<std::size_t, std::size_t>> peeled = peelLeaves(n, edges, kept);
  std::vector<PoseConstraint> core;
  for (std::size_t e = 0; e < edges.size(); ++e)
    if (kept[e]) core.push_back(edges[e]);
  PoseGraphProblem graph(T_world_node, core);

  PoseGraphResult out;
  out.T_world_node = T_world_node;
  out.initial_chi2 = totalChi2(T_world_node, edges);
  const std::vector<std::size_t> roots = pieceRoots(n, edges);
  std::vector<bool> touched(n, false);
  for (const PoseConstraint& c : edges) touched[c.from] = touched[c.to] = true;
  for (std::size_t i = 0; i < n; ++i) out.fixed_nodes += touched[i] && roots[i] == i ? 1 : 0;
  out.placed_nodes = peeled.size();
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
  if (core.empty()) {  // a tree: every node placed by its edge from its piece's root
    out.converged = true;
    out.message = "a tree: every node placed by its edge";
  } else {
    ceres::Solve(options, &graph.problem(), &summary);
    out.converged = summary.termination_type == ceres::CONVERGENCE;
    out.iterations = static_cast<int>(summary.iterations.size());
    out.message = summary.BriefReport();
  }
  for (std::size_t i = 0; i < n; ++i)
    if (graph.used(i)) out.T_world_node[i] = graph.pose(i);
  // The peeled nodes, the last peeled first: the node each hangs by is then placed.
  for (auto it = peeled.rbegin(); it != peeled.rend(); ++it) {
    const PoseConstraint& c = edges[it->second];
    if (it->first == c.to)
      out.T_world_node[c.to] = out.T_world_node[c.from] * c.T_from_to;
    else
      out.T_world_node[c.from] = out.T_world_node[c.to] * c.T_from_to.inverse();
  }
  out.final_chi2 = totalChi2(out.T_world_node, edges);
  return out;
}

}  // namespace gasp
