#pragma once
/// \file odometry_params.h Parameters of GASP's depth odometry (odometry.h), with their defaults
/// and units.
#include "gasp/odometry/scene_change.h"
#include "gasp/pipeline/pair_registration.h"
#include "gasp/pipeline/range_view.h"

namespace gasp {

struct OdometryParams {
  /// How each frame is segmented (pair.segment) and registered (everything else).
  PairParams pair;
  /// A tracked frame becomes the next keyframe when its pose is this far from its keyframe's
  /// [m] or turned by this much [deg]. Registering to a keyframe rather than to the previous
  /// frame keeps the small per-pair errors from adding up while the camera lingers (a hand-held
  /// camera moves about 1 cm per frame at 30 Hz); GASP registers views far apart, so keyframes
  /// may be sparse.
  double keyframe_distance_m = 0.10;
  double keyframe_angle_deg = 10.0;
  /// A registration implying a faster motion than this (over the time between the two frames)
  /// is not taken: no hand-held or robot camera moves so, a wrong pose may [m/s], [rad/s].
  double max_speed_mps = 3.0;
  double max_rate_radps = 3.0;
  /// Rolling-shutter readout of the depth sensor [s] (DeskewParams::readout_s; TUM's Kinect:
  /// 0.03, docs/pipeline.md "Rolling shutter"); 0 = off. Each frame is deskewed with the velocity
  /// of the last tracked step (frames i-2 -> i-1), so only the past is used.
  double rolling_shutter_readout_s = 0.0;
  /// A rotating LiDAR's sweep is carried to the sensor's pose at its start (deskewSweep(),
  /// range_scan.h): a sensor moving at 1 m/s moves 10 cm during a 10 Hz sweep. A sweep becoming
  /// the keyframe is deskewed with the velocity of the step that measured it; the sweeps tracked
  /// against it with that same velocity, so that the step between them sees no difference of
  /// deskews (deskewed with different velocities, a step is off by about their difference times
  /// the sweep, and the next velocity carries that on: the steps' errors oscillate and grow;
  /// docs/lidar.md "Motion within a sweep"). Only sweeps whose columns carry their times
  /// (sweepTimed(): a known duration, not a point cloud's azimuth bins).
  bool deskew_sweeps = false;
  /// A frame both attempts refuse, one of them for violating the other view's free space, is
  /// registered to the previous frame once more with looser visibility limits while the
  /// constant-velocity prediction is narrow enough, and taken when the pose lies within its
  /// gate (scene_change.h): a moved object or a person walking in no longer breaks the trajectory.
  SceneChangeParams scene_change;
  /// The tracking path (odometry.h): while the last step gave a velocity and the prediction's
  /// gate (scene_change's gate_m + max_accel_mps2 dt^2 / 2) lies within the dense rounds' last
  /// gate (pair.refine.dense.gates_m, 3 cm: frames at most 0.1 s apart with the defaults; the
  /// gate's translation only -- its rotation part is left to the certificate), a frame is first
  /// registered to its keyframe from the constant-velocity prediction by the dense rounds and the
  /// certificate alone (trackViews()), and taken when the certificate claims a full pose within
  /// the prediction's gate (scene_change's gate_m / gate_deg, grown with the time since the
  /// previous frame); otherwise by the whole pipeline. false: the whole pipeline for every frame.
  bool tracking = true;
};

/// Throws gasp::Error naming the first invalid parameter (including the pair's).
void validate(const OdometryParams& params);

/// The odometry for a rotating LiDAR's sweeps: `base`'s keyframe, motion and scene-change limits,
/// the pair's values of lidarPairParams(lidar, base.pair), and no rolling-shutter deskew (a sweep is not a
/// camera's image). Throws gasp::Error for invalid LiDAR parameters.
OdometryParams lidarOdometryParams(const LidarParams& lidar, const OdometryParams& base);
/// With the default odometry limits.
OdometryParams lidarOdometryParams(const LidarParams& lidar = {});

}  // namespace gasp
