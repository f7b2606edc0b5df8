#pragma once
/// \file pose_graph.h Pose-graph algebra shared by the loop closer and the optimiser: an edge's
/// chi-square, relative poses composed along the odometry's tree with their covariance, and
/// connected pieces. Perturbations as in gasp/core/pose_perturbation.h (PoseConstraint's
/// convention).
#include <cstddef>
#include <optional>
#include <vector>

#include "gasp/core/pose.h"
#include "gasp/core/pose_perturbation.h"
#include "gasp/odometry/pose_constraint.h"

namespace gasp {

/// The constraint's covariance, its information's inverse; throws gasp::Error when the
/// information is not finite and positive definite.
Matrix6d covarianceOf(const PoseConstraint& c);

/// The constraint's chi-square at the poses given: xi^T Lambda xi with
/// T_from^-1 T_to = Exp(xi) c.T_from_to, Lambda = c.information.
double edgeChi2(const Isometry3& T_world_from, const Isometry3& T_world_to, const PoseConstraint& c);

/// The loop closure an optimised graph contradicts most: among the edges with
/// PoseConstraint::loop_closure set, the one with the largest edgeChi2 at T_world_node above
/// gate_chi2 (the first such when several tie), as its index into `edges` and its chi-square.
/// Robust optimisation drops it and optimises again, until none is left (DepthSlam, the graph-SLAM
/// optimiser CGaspPoseGraphGSO). Throws gasp::Error for an edge naming a node out of range.
struct Contradiction {
  std::size_t edge = 0;
  double chi2 = 0.0;
};
std::optional<Contradiction> mostContradictedClosure(const std::vector<Isometry3>& T_world_node,
                                                     const std::vector<PoseConstraint>& edges, double gate_chi2);

/// A relative pose with its covariance (left perturbation in frame a) [m^2, m rad, rad^2].
struct RelativePoseEstimate {
  Isometry3 T_a_b = Isometry3::Identity();
  Matrix6d covariance = Matrix6d::Zero();
  std::size_t edges = 0;  ///< constraints on the path
};

/// T_a_b composed along the constraints of a tree (at most one constraint ends in each frame,
/// as the odometry's), through their lowest common ancestor, with the covariance of the path's
/// constraints (their informations' inverses) carried to frame a to first order. Empty when a
/// and b are in different pieces of the tree. Throws gasp::Error for a frame out of range, a
/// frame with two constraints ending in it, or an information that is not positive definite.
std::optional<RelativePoseEstimate> composeAlongTree(const std::vector<PoseConstraint>& tree, std::size_t frame_count,
                                                     std::size_t a, std::size_t b);

/// For each of `node_count` nodes, the lowest node index of its connected piece under `edges`
/// (edges naming nodes out of range throw gasp::Error).
std::vector<std::size_t> pieceRoots(std::size_t node_count, const std::vector<PoseConstraint>& edges);

/// Connected pieces of the graph (isolated nodes count as pieces; 0 without nodes).
std::size_t pieceCount(std::size_t node_count, const std::vector<PoseConstraint>& edges);

}  // namespace gasp
