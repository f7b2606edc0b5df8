#pragma once
/// \file graph_marginals.h The marginal covariance of each node of an MRPT engine's graph
/// (gasp/slam/pose_graph_marginals.h), as GASP's optimiser sees the graph: robot frames, each
/// edge's information converted from [x y z yaw pitch roll] to GASP's [t r] (constraintFromEdge).
/// Break edges (isBreakEdge: where the odometry lost track) constrain nothing and are left out,
/// so each piece of the graph is relative to its own lowest node, as in gasp-slam.
#include "gasp/graphslam/graph_types.h"
#include "gasp/slam/pose_graph_marginals.h"

namespace gasp::graphslam {

/// Node IDs must be 0 .. N-1 (as the engine numbers them); throws gasp::Error otherwise, and for
/// an edge naming a node outside the graph. The covariances are over the left perturbation of the
/// robot pose in the world, which is also the camera pose's (T_world_camera = T_world_robot
/// T_robot_camera, moved on the left).
PoseGraphMarginals graphMarginals(const Graph3D& graph);

}  // namespace gasp::graphslam
