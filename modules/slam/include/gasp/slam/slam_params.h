#pragma once
/// \file slam_params.h Parameters of GASP's depth SLAM (depth_slam.h): the odometry's, the loop
/// closer's and the pose-graph optimiser's, with their defaults and units.
#include <cstddef>

#include "gasp/odometry/odometry_params.h"
#include "gasp/pipeline/range_view.h"
#include "gasp/slam/pose_graph_optimizer.h"

namespace gasp {

/// How loop-closure candidates are chosen: near the new keyframe at the current estimate, by the
/// nearest place descriptors over the whole map (place_descriptor.h; DepthSlam only), or both.
enum class LoopSearch { kRadius, kRetrieval, kBoth };

struct LoopClosureParams {
  bool enabled = true;  ///< false: odometry only (the graph is then a tree and never optimised)
  /// Candidates: earlier keyframes of the same graph piece within this distance of the new
  /// keyframe, at the current estimate [m]. GASP needs no initial guess, so the radius only
  /// bounds the search; the views must still overlap.
  double search_radius_m = 0.5;
  /// ...whose optical axes are at most this far apart [deg]; a roll about the axis does not count
  /// (GASP registers 180-degree rolls).
  double max_axis_angle_deg = 45.0;
  /// Keyframes this close in the sequence to the new one are not candidates: the odometry
  /// already links them. Candidates chosen together are also this far apart from each other.
  std::size_t min_keyframe_gap = 5;
  std::size_t max_candidates = 2;  ///< registrations per new keyframe, nearest first
  /// A loop closure is taken when the registration succeeds with at least `min_inliers` inliers
  /// and agrees with the odometry: xi^T (S_path + S_meas)^-1 xi <= gate_chi2, xi the difference
  /// between the measured and the predicted relative pose, S_path the covariance of the odometry
  /// constraints between the two keyframes, S_meas the closure's. The default is the chi-square
  /// quantile of 6 degrees of freedom at 0.999. After each optimisation, a closure whose own
  /// chi-square exceeds it is dropped and the graph optimised again.
  int min_inliers = 20;
  double gate_chi2 = 22.46;
  /// Relocalisation: when the odometry lost track and the graph fell into pieces, each new
  /// keyframe is also registered, with no pose prior, to the latest keyframes of the other
  /// pieces (at most this many); a success with at least `relocalisation_min_inliers` inliers
  /// is a vote. 0 = off.
  std::size_t relocalisation_candidates = 3;
  int relocalisation_min_inliers = 40;
  /// Two pieces are joined when this many votes link them consistently (relocalisation.h: each
  /// waiting vote predicts the new one through the odometry inside the two pieces, within
  /// gate_chi2). 1: the first vote joins them, as a single registration with no pose prior
  /// that the optimised graph can never contradict. At most kMaxRelocalisationAgreeing (the
  /// search for agreeing votes looks at the best kMaxRelocalisationAgreeing - 1 waiting ones).
  std::size_t relocalisation_agreeing = 2;
  static constexpr std::size_t kMaxRelocalisationAgreeing = 25;
  /// DepthSlam registers a keyframe's candidates on a thread of its own while the next frames are
  /// tracked, and takes the results when they are ready (depth_slam.h); false: in place, the
  /// tracking waiting for them. The graph-SLAM plugin's edge decider always searches in place.
  bool background = true;
  LoopSearch search = LoopSearch::kRadius;
  /// Retrieval: the keyframes with the nearest place descriptors taken as candidates (at least
  /// min_keyframe_gap keyframes back, in the new keyframe's piece), besides the radius's with kBoth.
  std::size_t retrieval_candidates = 2;
};

struct SlamParams {
  OdometryParams odometry;
  LoopClosureParams loop;
  PoseGraphSettings graph;
  LidarParams lidar;  ///< for rotating-LiDAR sweeps (range_view.h): their pair values follow from these
};

/// Throws gasp::Error naming the first invalid parameter (including the odometry's).
void validate(const LoopClosureParams& params);
void validate(const SlamParams& params);

/// The parameters for a rotating LiDAR's sweeps: `params` with its odometry's pair values those of
/// its `lidar` section (lidarOdometryParams(params.lidar, params.odometry)); the loop closer's and
/// the graph's as given. Throws gasp::Error for invalid LiDAR parameters.
SlamParams lidarSlamParams(const SlamParams& params);

}  // namespace gasp
