#pragma once
/// \file pose_constraint.h One edge of a pose graph: the relative pose between two frames of a
/// sequence with its information, as GASP measured it.
#include <cstddef>

#include "gasp/core/pose.h"
#include "gasp/registration/registration_result.h"

namespace gasp {

struct PoseConstraint {
  std::size_t from = 0;  ///< frame index (the pair's target view)
  std::size_t to = 0;    ///< frame index (the pair's source view)
  /// Pose of frame `to` in frame `from` (p_from = T_from_to p_to): the pair's T_target_source
  /// with target = from, source = to. A graph's edge from -> to, as MRPT's CNetworkOfPoses stores it.
  Isometry3 T_from_to = Isometry3::Identity();
  /// PairResult::edge_information: order [tx ty tz rx ry rz] of the left perturbation
  /// T_from_to <- Exp(xi) T_from_to in frame `from` (registration_result.h), with the model error
  /// added (model_error.h) [1/m^2, 1/(m rad), 1/rad^2].
  Matrix6d information = Matrix6d::Zero();
  int inliers = 0;            ///< RANSAC inliers behind the pose
  bool loop_closure = false;  ///< false: odometry (a frame against its keyframe or predecessor)
  /// Odometry taken through a scene change (scene_change.h): the views contradict each other's
  /// free space beyond the pair's limits, and the constant-velocity prediction vouched for the
  /// pose. The information is GASP's as for any edge (docs/odometry.md, "Scenes that change");
  /// a back-end may weigh such edges down.
  bool scene_change = false;
  /// Odometry through a partial pose (certify_stage.h): GASP observed only some directions; the
  /// others are the motion prediction's. `information` is GASP's in the observed directions plus
  /// the prediction's in the free ones (docs/odometry.md "Views that fix only part of the pose").
  int free_directions = 0;
};

}  // namespace gasp
