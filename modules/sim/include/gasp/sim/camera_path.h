#pragma once
/// \file camera_path.h The simulator's deterministic camera trajectory with labelled segments.
#include <string>
#include <vector>

#include "gasp/core/pose.h"
#include "gasp/core/tum_trajectory.h"

namespace gasp::sim {

/// Segment names of the camera path, in path order.
inline const char* const kWideBaseline = "wide_baseline";        ///< >= 1 m and >= 30 deg yaw
inline const char* const kPartialOverlap = "partial_overlap";    ///< ~45 deg pan (partial overlap)
inline const char* const kOccluderAppears = "occluder_appears";  ///< an occluder appears midway
inline const char* const kRoll180 = "roll_180";                  ///< 180 deg about the optical axis

/// Frames [first_frame, last_frame] (inclusive) of a named part of the path. Consecutive
/// segments share their boundary frame.
struct TrajectorySegment {
  std::string name;
  int first_frame = 0;
  int last_frame = 0;
};

/// Camera poses (T_world_camera of the optical frame, one per frame) and the segments.
struct CameraPath {
  Trajectory poses;
  std::vector<TrajectorySegment> segments;

  int size() const { return static_cast<int>(poses.size()); }
  /// The segment with that name; throws gasp::Error listing the names otherwise.
  const TrajectorySegment& segment(const std::string& name) const;
};

/// Parameters of makeCameraPath().
struct CameraPathOptions {
  int frames = 60;              ///< number of frames (>= kMinPathFrames)
  double start_time_s = 1000.0;  ///< timestamp of frame 0 [s]
  double rate_hz = 30.0;         ///< frame rate [Hz]; timestamps are rounded to microseconds
};

/// Fewest frames makeCameraPath() accepts (each segment needs at least one step).
constexpr int kMinPathFrames = 8;
/// Most frames (about 6 GB of depth and rgb PNGs for a TUM folder).
constexpr int kMaxPathFrames = 20000;
/// Frame rates accepted [Hz]: timestamps in microseconds stay distinct and short.
constexpr double kMinRateHz = 0.001;
constexpr double kMaxRateHz = 10000.0;

/// The path through five waypoints (world z up): segments wide_baseline, partial_overlap,
/// occluder_appears and roll_180 get 30%, 25%, 20% and 25% of the frames. Between waypoints the
/// position is interpolated linearly, the look-at orientation by slerp, and the roll about the
/// optical axis linearly (so the 180-degree roll is not short-cut). Throws gasp::Error when
/// frames is outside [kMinPathFrames, kMaxPathFrames] or the rate outside [kMinRateHz, kMaxRateHz].
CameraPath makeCameraPath(const CameraPathOptions& options = {});

/// Segment name of a hand-held path: all of it.
inline const char* const kHandHeld = "hand_held";

/// A camera held by hand over a scene (the plane-dominated scenes): held at `eye` and looking at
/// `target`, it wanders as a hand does, each coordinate of the eye and of the look-at point a
/// sum of slow sines of incommensurate periods (never repeating within a sequence), with a roll
/// about the optical axis, and both may drift at a constant velocity (a walk along a corridor).
/// With the defaults the camera moves at most about 0.3 m/s and, looking down at a floor, turns
/// at up to about 60 deg/s: pairs 5, 10 and 20 frames apart at 30 Hz are a few to about 30 cm
/// apart.
struct HandHeldView {
  Eigen::Vector3d eye{0.0, 0.0, 1.2};     ///< [m], world (z up)
  Eigen::Vector3d target{0.7, 0.0, 0.0};  ///< [m]
  double sweep_m = 0.3;       ///< amplitude of the eye's horizontal wander [m]
  double bob_m = 0.05;        ///< amplitude of its vertical wander [m]
  double look_sweep_m = 0.2;  ///< amplitude of the look-at point's horizontal wander [m]
  double roll_deg = 6.0;      ///< amplitude of the roll about the optical axis [deg]
  double period_s = 9.0;      ///< period of the slowest sine [s]
  Eigen::Vector3d drift_mps = Eigen::Vector3d::Zero();  ///< eye and target move at this velocity [m/s]
};

/// The hand-held path over `options.frames` frames, one segment (kHandHeld). Throws gasp::Error
/// as makeCameraPath for the frames and rate, and for a view whose amplitudes or period are not
/// finite and >= 0 (> 0 for the period) or that looks along the vertical.
CameraPath makeHandHeldPath(const HandHeldView& view, const CameraPathOptions& options = {});

/// One waypoint of a walk: the camera at `position` looking at `target`; `leg` names the part of
/// the walk from this waypoint to the next (a segment of the path; empty for the last).
struct WalkWaypoint {
  Eigen::Vector3d position;  ///< [m], world (z up)
  Eigen::Vector3d target;    ///< [m]
  std::string leg;
};

/// A walk through waypoints at a steady pace (scenes walked through, e.g. two_rooms): each leg
/// gets frames in proportion to its effort, its length plus kWalkMetresPerRadian times the angle
/// the view turns, so a turn on the spot takes time too; between waypoints the position is
/// interpolated linearly and the orientation by slerp. One segment per leg, named by it. Throws
/// gasp::Error as makeCameraPath for the frames and rate, for fewer than two waypoints, fewer
/// frames than waypoints, and a waypoint that is not finite or looks along the vertical.
CameraPath makeWalkPath(const std::vector<WalkWaypoint>& walk, const CameraPathOptions& options = {});
inline constexpr double kWalkMetresPerRadian = 0.5;

/// Optical camera pose at `position` looking at `target` with world `up` (image y points down),
/// then rolled by roll_rad about the optical axis. Throws gasp::Error when the viewing direction
/// is zero or parallel to up.
Isometry3 lookAt(const Eigen::Vector3d& position, const Eigen::Vector3d& target, double roll_rad = 0.0,
                 const Eigen::Vector3d& up = Eigen::Vector3d::UnitZ());

/// The pose on `poses` (sorted, strictly increasing timestamps) at time t [s]: between two poses
/// the position interpolated linearly and the orientation by slerp (a constant velocity between
/// frames); before the first pose, the first; past the last, the last step's motion continued at
/// its velocity (a sensor still moving at the end of the path). Throws gasp::Error for fewer than
/// two poses, timestamps that do not increase strictly, or a t that is not finite.
Isometry3 poseAtTime(const Trajectory& poses, double t);

}  // namespace gasp::sim
