#pragma once
/// \file odometry.h GASP over a sequence of depth frames: camera odometry and the pose-graph
/// constraints a graph-SLAM back-end consumes.
///
/// Each frame is segmented once (superpixels) and registered to the current keyframe: first by
/// the tracking path (trackViews(): dense rounds from the constant-velocity prediction, certified,
/// within the prediction's gate) when a velocity is known, else or when that fails by the whole
/// pair front-end (registerViews()). When that gives no estimate, it is registered to the frame
/// before it, and then becomes the keyframe. When neither gives one, its pose is predicted with
/// the last measured velocity and marked as not tracked: the trajectory goes on, the pose graph
/// has no edge to it from the past (a break) -- unless the scene changed and the motion prediction
/// vouches for a pose found with looser visibility limits (scene_change.h). Every measured pose
/// is a PoseConstraint with GASP's edge information, so the constraints form a tree over the frames, to which a back-end adds
/// loop closures.
///
/// Deterministic: the same frames and parameters give the same poses, whatever the thread count
/// (registerViews() is).
#include <opencv2/core.hpp>

#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "gasp/core/camera_intrinsics.h"
#include "gasp/core/pose.h"
#include "gasp/core/range_scan.h"
#include "gasp/core/rolling_shutter.h"
#include "gasp/core/tum_trajectory.h"
#include "gasp/odometry/odometry_params.h"
#include "gasp/odometry/pose_constraint.h"
#include "gasp/odometry/view_ahead.h"
#include "gasp/pipeline/depth_view.h"
#include "gasp/pipeline/edge_terms.h"

namespace gasp {

/// What the odometry did with one frame.
struct OdometryFrame {
  std::size_t index = 0;
  std::size_t session = 0;  ///< the session it belongs to (DepthOdometry::startSession()), from 0
  double timestamp = 0.0;  ///< [s]
  Isometry3 T_world_camera = Isometry3::Identity();  ///< world = the first frame's camera (or as given)
  /// The pose was measured by GASP against `reference` (the first frame with patches: the origin,
  /// tracked by definition). false: predicted with the last velocity (or standing still without one).
  bool tracked = false;
  bool keyframe = false;       ///< later frames are registered to this one
  std::size_t reference = 0;   ///< the frame it was registered to (its own index when not tracked)
  /// Why each failed attempt failed: not tracked, or tracked against the previous frame after
  /// the keyframe failed (empty when the keyframe gave the pose).
  std::string reason;
  int patches = 0;             ///< superpixels of the frame
  int inliers = 0;             ///< RANSAC inliers of the pose (0 when not tracked, and on the tracking path)
  /// Tracked through a scene change (scene_change.h): no strict attempt gave a pose and the
  /// visibility check refused one of theirs; the pose is the scene-change attempt's against the
  /// previous frame, within the gate of the constant-velocity prediction. `reason` says why the
  /// strict attempts failed and what the scene-change attempt measured. The frame becomes the
  /// keyframe.
  bool scene_change = false;
  /// Tracked with a partial pose (certify_stage.h): GASP fixed only some directions against the
  /// reference (a floor, a wall, a corridor); the free ones (free_directions of them) are the
  /// constant-velocity prediction's. `reason` names them.
  bool partial = false;
  int free_directions = 0;
  /// The pose came from the tracking path (OdometryParams::tracking): dense rounds from the
  /// constant-velocity prediction against the keyframe, certified; no association or RANSAC.
  bool tracking_path = false;
  bool deskewed = false;  ///< deskewed before segmenting: a camera's rolling shutter, a sweep's turn
  double segmentation_ms = 0.0;  ///< deskew + superpixels
  double registration_ms = 0.0;  ///< all registration attempts
};

/// One frame as a DepthOdometry tracked it, for another one to take (DepthOdometry::addTracked()):
/// a session tracked in one process and replayed, unchanged, in another (a map-building job
/// spread over processes, depth_slam.h). Bytes: trackedFrameBytes() (tracked_frame_bytes.h).
struct TrackedFrame {
  OdometryFrame frame;                       ///< numbered as the odometry that tracked it numbered it
  std::optional<PoseConstraint> constraint;  ///< the constraint ending in it (tracked, not its session's origin)
  std::optional<DepthView> keyframe_view;    ///< its view, when it became the keyframe
};

class DepthOdometry {
 public:
  /// Throws gasp::Error for invalid parameters. T_world_first: the first frame's pose.
  explicit DepthOdometry(const OdometryParams& params = {},
                         const Isometry3& T_world_first = Isometry3::Identity());

  /// Adds the next frame: depth [m] (CV_32FC1, 0 or NaN = no data; lens distortion in the
  /// intrinsics is resampled away as in makeDepthView()). A frame without usable depth (no
  /// surface patch) is not tracked, with the reason; the first frame with patches is the origin.
  /// Throws gasp::Error, and does not add the frame, for a timestamp that is not finite or not
  /// later than the previous frame's of its session, an empty image, or one whose size or type does not match
  /// its intrinsics.
  /// `segmented`: the frame's view made ahead from the same depth and intrinsics (ViewAhead,
  /// view_ahead.h), used when the frame is not deskewed (else, or when empty, the frame is
  /// segmented here).
  const OdometryFrame& addFrame(double timestamp, const cv::Mat& depth_m, const CameraIntrinsics& intrinsics,
                                std::optional<SegmentedDepth> segmented = std::nullopt);
  /// Adds the next frame as a rotating LiDAR's sweep (range_view.h: binned, segmented with
  /// params.pair.segment, its returns kept for the pairs' last stage with params.pair.returns;
  /// lidarOdometryParams() are a LiDAR's). Poses are the sensor's (MRPT's LiDAR frame, x ahead,
  /// z up), at the sweep's start (`timestamp`). With params.deskew_sweeps, a sweep whose columns
  /// carry their times is carried to that pose (deskewSweep(), range_scan.h;
  /// OdometryFrame::deskewed) with the velocity its keyframe's sweep was deskewed with, and, when
  /// it becomes the keyframe, again with the step that measured it (odometry_params.h). Throws gasp::Error when rolling_shutter_readout_s is
  /// not 0 (a camera's), for a scan that is not a range image, and for timestamps as above.
  /// `segmented`: its view made ahead (ViewAhead::start(const RangeScan&)), used when the sweep is
  /// not deskewed.
  const OdometryFrame& addFrame(double timestamp, const RangeScan& sweep,
                                std::optional<SegmentedDepth> segmented = std::nullopt);

  /// The last frame added (frames().back()) with its constraint and, when it became the keyframe,
  /// its view: what addTracked() of another odometry takes. Throws gasp::Error before any frame.
  TrackedFrame lastTracked() const;
  /// Adds a frame another DepthOdometry tracked (lastTracked()), as it tracked it: the same pose,
  /// constraint, keyframe and reasons, renumbered after this odometry's frames. That odometry had
  /// the same parameters, started the frame's session at the T_world_first this session has, and
  /// tracked nothing but that session (its frames since the session's start are this session's,
  /// in order); then the frames are those addFrame() would have made. A session's frames come all
  /// from addFrame() or all from addTracked(): a replayed session has no views to track the next
  /// frame against. Throws gasp::Error, and does not add the frame, for what the odometry never
  /// makes: a timestamp addFrame() refuses, a frame out of its session's order, a reference or
  /// constraint outside its session, a keyframe without its view or not tracked, a second origin or
  /// one away from T_world_first, a pose or constraint not finite or a loop closure. (That the
  /// parameters were the same cannot be checked here.)
  const OdometryFrame& addTracked(TrackedFrame tracked);

  /// Starts a new session (another recording, with no known relation to the frames before): the
  /// next frame with patches is its origin, at T_world_first, as the first frame is the first
  /// session's; nothing of the previous session (keyframe, velocity, timestamps) is used, so the
  /// sessions are pieces of the pose graph of their own until a loop closer joins them. While the
  /// current session has no frame, only its T_world_first changes.
  void startSession(const Isometry3& T_world_first);
  /// The first frame of each session (0 for the first); a session with no frame yet is not listed.
  const std::vector<std::size_t>& sessionStarts() const { return session_starts_; }

  const std::vector<OdometryFrame>& frames() const { return frames_; }
  /// One per tracked frame after the first (from = its reference, to = the frame), in frame order.
  const std::vector<PoseConstraint>& constraints() const { return constraints_; }
  /// Every frame's pose (tracked or predicted), in frame order.
  Trajectory trajectory() const;
  std::size_t trackedCount() const;
  /// Frames tracked through a scene change (OdometryFrame::scene_change).
  std::size_t sceneChangeCount() const;
  std::size_t keyframeCount() const;
  /// Connected pieces of the pose graph the constraints make over all frames: 1 when every frame
  /// is linked to the first, 0 without frames. A lost frame that no later frame is registered to
  /// is a piece of its own; one that the next frame is registered to (the keyframe failed) starts
  /// a new piece with the frames after it.
  std::size_t componentCount() const;
  const OdometryParams& params() const { return params_; }
  /// The current keyframe's segmented view (that of the last frame with `keyframe` set; deskewed
  /// when the frame was); nullptr before the first. A loop closer keeps copies (depth_slam.h).
  const DepthView* keyframeView() const { return keyframe_view_ ? &*keyframe_view_ : nullptr; }

 private:
  /// Registers `view` (frame i at time t) to `ref` with `pair`; on success sets f's pose and adds
  /// the constraint. With `T_ref_predicted` (the scene-change attempt) the pose must also lie
  /// within the gate of that prediction (predictionGate()).
  /// `visibility_refused` (when given) is set when the visibility check refused the pose it found.
  /// `T_ref_motion` (when given): the motion model's prediction of the frame in `ref`'s frame, which
  /// holds a partial pose's free directions (without it a partial pose is not taken).
  bool track(const DepthView& view, const DepthView& ref, std::size_t ref_index, OdometryFrame& f,
             const char* attempt, const PairParams& pair, const std::optional<Isometry3>& T_ref_predicted = std::nullopt,
             bool* visibility_refused = nullptr, const std::optional<Isometry3>& T_ref_motion = std::nullopt);
  /// Throws gasp::Error for a timestamp addFrame() refuses, and for a frame to track here or
  /// replayed (`tracked_elsewhere`) when the current session's frames are the other kind.
  void checkNext(double timestamp, bool tracked_elsewhere) const;
  /// addFrame() once the frame's view is made; `sweep`: the LiDAR sweep it was made from (as read),
  /// deskewed again when it becomes the keyframe (OdometryParams::deskew_sweeps).
  const OdometryFrame& addView(double timestamp, DepthView view, double segmentation_ms, bool deskewed,
                               const RangeScan* sweep = nullptr);
  /// track() with the registration `r` (T_ref_frame) already made.
  bool take(PairResult r, std::size_t ref_index, OdometryFrame& f, const char* attempt,
            const std::optional<Isometry3>& T_ref_predicted = std::nullopt, bool* visibility_refused = nullptr,
            const std::optional<Isometry3>& T_ref_motion = std::nullopt);

  OdometryParams params_;
  Isometry3 T_world_first_;
  std::vector<OdometryFrame> frames_;
  std::vector<PoseConstraint> constraints_;
  std::optional<DepthView> keyframe_view_;
  /// The keyframe's edge targets for the tracking path, built at its first tracked frame (shared:
  /// immutable, and the odometry stays copyable).
  std::shared_ptr<const EdgeTargets> keyframe_edges_;
  std::size_t keyframe_index_ = 0;
  std::optional<DepthView> previous_view_;
  /// Velocity of the last step (frames i-1 -> i) when both were tracked and it was plausible, in
  /// the camera's frame; empty otherwise.
  std::optional<CameraTwist> velocity_;
  /// The velocity the keyframe's sweep was deskewed with (deskew_sweeps); empty: not deskewed. The
  /// sweeps tracked against it are deskewed with the same.
  std::optional<CameraTwist> keyframe_deskew_;
  std::vector<std::size_t> session_starts_;  ///< as sessionStarts()
  bool session_pending_ = false;             ///< startSession() called: the next frame starts one
  bool session_replayed_ = false;            ///< the current session's frames came from addTracked()
  /// addTracked(): the first frame of the current session as its own odometry numbered it.
  std::size_t replay_offset_ = 0;
};

}  // namespace gasp
