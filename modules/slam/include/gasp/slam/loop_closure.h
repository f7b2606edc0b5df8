#pragma once
/// \file loop_closure.h Which earlier keyframes a new keyframe is registered to, and what came of
/// each attempt.
#include <cstddef>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "gasp/core/pose.h"
#include "gasp/odometry/pose_constraint.h"
#include "gasp/pipeline/depth_view.h"
#include "gasp/pipeline/pair_registration.h"
#include "gasp/slam/pose_graph.h"
#include "gasp/slam/slam_params.h"

namespace gasp {

/// One registration of a new keyframe (`to`) against an earlier one (`from`).
struct LoopClosureAttempt {
  std::size_t from = 0;         ///< the earlier keyframe (the pair's target view)
  std::size_t to = 0;           ///< the new keyframe (the pair's source view)
  bool relocalisation = false;  ///< `from` was in another piece of the graph: no pose prior
  bool accepted = false;        ///< in the graph (false also when dropped after an optimisation)
  int inliers = 0;              ///< RANSAC inliers (0 without an estimate)
  /// The consistency statistic: against the odometry (loop closures), or the least against the
  /// waiting relocalisations between the same pieces (relocalisations, relocalisation.h); NaN
  /// when there was nothing to check against or the registration gave no estimate.
  double gate_chi2 = std::numeric_limits<double>::quiet_NaN();
  double registration_ms = 0.0;
  std::string reason;  ///< why it was not taken, or dropped
};

/// Loop-closure candidates for keyframe `current`, nearest first: earlier keyframes of the same
/// piece (`piece_root`, pose_graph.h's pieceRoots()) at least `min_keyframe_gap` keyframes back,
/// within `search_radius_m` at the poses given and with optical axes (camera z) at most
/// `max_axis_angle_deg` apart; at most `max_candidates`, at least `min_keyframe_gap` keyframes
/// apart from each other. `keyframes`: the keyframes' frame indices, ascending, `current` last.
std::vector<std::size_t> loopCandidates(const std::vector<std::size_t>& keyframes,
                                        const std::vector<Isometry3>& T_world_frame,
                                        const std::vector<std::size_t>& piece_root, const LoopClosureParams& params);

/// Relocalisation candidates for the last of `keyframes`, at most `relocalisation_candidates`:
/// the latest keyframe of each other piece (the most recent piece first), then the second
/// latest of each, and so on, so that one recent piece cannot take every slot.
std::vector<std::size_t> relocalisationCandidates(const std::vector<std::size_t>& keyframes,
                                                  const std::vector<std::size_t>& piece_root,
                                                  const LoopClosureParams& params);

/// Registers view `to_view` (keyframe `to`, the pair's source) to `from_view` (keyframe `from`,
/// the target) with the whole pair front-end and no initial guess. Returns the attempt, its
/// reason set when there is no estimate or fewer inliers than `min_inliers` (or
/// `relocalisation_min_inliers`), and in `c` the constraint from -> to (loop_closure set) with
/// PairResult::edge_information.
LoopClosureAttempt registerLoopClosure(const DepthView& from_view, const DepthView& to_view, std::size_t from,
                                       std::size_t to, bool relocalisation, const PairParams& pair,
                                       const LoopClosureParams& params, PoseConstraint& c);

/// The gate of a registered loop closure `c` (its attempt `a` without a reason yet) against
/// the odometry's prediction of the same relative pose: sets a.gate_chi2 = xi^T (S_path +
/// S_meas)^-1 xi and a reason when it exceeds params.gate_chi2. Without a prediction (the two
/// keyframes are joined only through other loop closures), the closure needs
/// relocalisation_min_inliers instead.
void gateLoopClosure(const PoseConstraint& c, const std::optional<RelativePoseEstimate>& prediction,
                     const LoopClosureParams& params, LoopClosureAttempt& a);

}  // namespace gasp
