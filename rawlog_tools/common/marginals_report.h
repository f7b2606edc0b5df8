#pragma once
/// \file marginals_report.h What gasp-slam prints and writes about the uncertainty of its poses:
/// the pose graph's marginal covariances (gasp/slam/pose_graph_marginals.h).
#include <ostream>
#include <string>

#include "gasp/core/tum_trajectory.h"
#include "gasp/slam/pose_graph_marginals.h"

namespace gasp::tools {

/// 1-sigma sizes of a [t r] covariance of T_world: sqrt of the trace of the position's covariance
/// (positionCovariance(), the root-mean-square length of the position error in 3D) [m] and of
/// the rotation block's [deg].
struct Sigma {
  double t_m = 0.0, r_deg = 0.0;
};
Sigma sigmaOf(const Matrix6d& covariance, const Isometry3& T_world);

/// Prints "marginals: N <what>s (MS ms); largest at <what> F: 1-sigma T m / R deg (relative to
/// <what> ROOT)", or "marginals: not computed (REASON)"; <what> is "frame" or "node". With ground truth (matched by timestamp
/// within 20 ms), also "marginals_nees: median M, 95 % Q over N frames (chi-square, 6 degrees of
/// freedom: median 5.35, 95 % 12.59)": each one's error against the ground truth moved to agree
/// at its piece's root, T_ref_i = T_root T_gt_root^-1 T_gt_i, weighed by its covariance's
/// inverse (gasp::eval::nees). `estimate` holds every frame's timestamp and pose, in frame order.
void printMarginals(const PoseGraphMarginals& marginals, const Trajectory& estimate, const Trajectory& ground_truth,
                    const std::string& what = "frame");

/// One line per frame with a covariance: frame,timestamp,root,sigma_t_m,sigma_r_deg (sigmaOf():
/// the position's and the rotation's), then the 36 entries c00..c55 (row-major) of the
/// covariance of the left perturbation [tx ty tz rx ry rz] in the world [m^2, m rad, rad^2], into
/// `out` (RunOutputs' file; its commit() checks the writes).
void writeMarginalsCsv(std::ostream& out, const PoseGraphMarginals& marginals, const Trajectory& estimate);

}  // namespace gasp::tools
