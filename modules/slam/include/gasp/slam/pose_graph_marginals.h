#pragma once
/// \file pose_graph_marginals.h How well a pose graph pins each node down: the marginal covariance
/// of every node at the poses given (normally the optimiser's output, pose_graph_optimizer.h),
/// the node's diagonal block of (J^T J)^-1 with J the Jacobian of the optimiser's whitened
/// residuals r_e = L_e^T xi_e (Lambda_e = L_e L_e^T). Computed with ceres::Covariance (sparse QR)
/// on the optimiser's own cost, so the two cannot disagree.
///
/// Gauge: the optimiser's. The lowest-index node of each connected piece is held fixed, so a
/// node's covariance is its uncertainty relative to that node, the piece's root (zero there).
/// Convention: left perturbation in the world, T_world_node = Exp(xi) T_hat, xi = [t r]
/// ([m], [rad]; gasp/core/pose_perturbation.h), as PoseConstraint's information.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "gasp/core/pose.h"
#include "gasp/odometry/pose_constraint.h"

namespace gasp {

struct PoseGraphMarginals {
  /// Per node: its covariance [m^2, m rad, rad^2] relative to its piece's root; zero at a root;
  /// nullopt for a node no edge touches (nothing constrains it) and for every node when
  /// `computed` is false.
  std::vector<std::optional<Matrix6d>> covariance;
  std::vector<std::size_t> piece_root;  ///< per node, the node its covariance is relative to
  bool computed = false;  ///< false when Ceres could not compute it (see message)
  std::string message;    ///< why not computed; empty otherwise
  double ms = 0.0;        ///< wall time
};

/// The covariance of the position (the translation of T_world_node) from a [t r] covariance of the
/// left perturbation: Exp(xi) T moves the position by t + r x p, so C_p = B C B^T with
/// B = [I, -[p]x]. (The [t] block alone is not the position's: a rotation about the world's
/// origin moves the position with t = 0.)
Eigen::Matrix3d positionCovariance(const Matrix6d& covariance, const Isometry3& T_world_node);

/// Throws gasp::Error for the graphs optimizePoseGraph() refuses (a node or edge not finite, an
/// edge out of range or linking a node to itself, an information not positive definite).
PoseGraphMarginals poseGraphMarginals(const std::vector<Isometry3>& T_world_node,
                                      const std::vector<PoseConstraint>& edges, int num_threads = 1);

}  // namespace gasp
