#pragma once
/// \file pose_graph_optimizer.h Least-squares optimisation of a pose graph (Ceres): the node poses
/// that best agree with every constraint under its information,
///   min sum_e xi_e^T Lambda_e xi_e,  T_from^-1 T_to = Exp(xi_e) T_from_to (pose_graph.h),
/// with each rotation on the unit-quaternion manifold. The gauge: the lowest-index node of each
/// connected piece is held fixed, so a piece keeps its place and pieces do not move each other.
/// Nodes that hang by one edge (and the branches they end) are not unknowns: at the optimum each
/// is where its edge puts it, so they are placed so once the rest is optimised (the same
/// optimum; an odometry's frames between keyframes are such nodes, so a sequence's graph is
/// optimised over its keyframes).
#include <cstddef>
#include <string>
#include <vector>

#include "gasp/core/pose.h"
#include "gasp/odometry/pose_constraint.h"

namespace gasp {

struct PoseGraphSettings {
  int max_iterations = 100;           ///< Levenberg-Marquardt iterations
  double function_tolerance = 1e-10;  ///< relative cost change that ends the solve
  int num_threads = 1;                ///< Ceres threads (the graph is small beside registration)
};

/// Throws gasp::Error unless max_iterations, num_threads and function_tolerance are positive.
void validate(const PoseGraphSettings& settings);

struct PoseGraphResult {
  std::vector<Isometry3> T_world_node;  ///< optimised; nodes without an edge keep their input pose
  bool converged = false;  ///< Ceres converged (true with nothing to optimise)
  int iterations = 0;
  double initial_chi2 = 0.0;  ///< sum of edgeChi2 over the edges at the input poses
  double final_chi2 = 0.0;    ///< the same at the output poses
  std::size_t fixed_nodes = 0;  ///< one per connected piece with an edge
  std::size_t placed_nodes = 0;  ///< nodes placed by the one edge they hang by, not optimised
  std::string message;          ///< Ceres's summary line
};

/// Throws gasp::Error for an edge naming a node out of range or linking a node to itself, a
/// non-finite pose or information, or an information that is not positive definite.
PoseGraphResult optimizePoseGraph(const std::vector<Isometry3>& T_world_node, const std::vector<PoseConstraint>& edges,
                                  const PoseGraphSettings& settings = {});

}  // namespace gasp
