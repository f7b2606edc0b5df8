#include "gasp/odometry/odometry.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <utility>

#include "gasp/core/error.h"
#include "gasp/core/pose_perturbation.h"
#include "gasp/core/stopwatch.h"
#include "gasp/core/undistortion.h"
#include "gasp/pipeline/pair_registration.h"
#include "gasp/pipeline/range_view.h"
#include "gasp/registration/partial_pose.h"

namespace gasp {

namespace {

/// The camera's motion over dt at a constant twist (first order in the translation, as twistBetween()).
Isometry3 stepOf(const CameraTwist& twist, double dt) {
  Vector6 xi;
  xi << twist.v_mps * dt, twist.w_radps * dt;
  return expLeft(xi);
}

/// Empty when the motion T_a_b over dt seconds is plausible, else why not.
std::string implausibleMotion(const Isometry3& T_a_b, double dt, const OdometryParams& p) {
  const double speed = translationNorm(T_a_b) / dt, rate = rotationAngle(T_a_b) / dt;
  if (speed <= p.max_speed_mps && rate <= p.max_rate_radps) return {};
  char buf[160];
  std::snprintf(buf, sizeof buf, "implausible motion: %.2f m/s, %.2f rad/s over %.3f s", speed, rate, dt);
  return buf;
}

}  // namespace

DepthOdometry::DepthOdometry(const OdometryParams& params, const Isometry3& T_world_first)
    : params_(params), T_world_first_(T_world_first) {
  validate(params_);
}

void DepthOdometry::startSession(const Isometry3& T_world_first) {
  T_world_first_ = T_world_first;
  if (frames_.empty() || session_pending_) return;  // the current session has no frame yet
  session_pending_ = true;
  keyframe_view_.reset();
  keyframe_edges_.reset();
  keyframe_index_ = 0;
  previous_view_.reset();
  velocity_.reset();
  keyframe_deskew_.reset();
}

TrackedFrame DepthOdometry::lastTracked() const {
  if (frames_.empty()) throw Error("odometry: no frame to hand over yet");
  TrackedFrame t;
  t.frame = frames_.back();
  if (t.frame.tracked && t.frame.reference != t.frame.index) t.constraint = constraints_.back();
  if (t.frame.keyframe) t.keyframe_view = keyframe_view_;
  return t;
}

const OdometryFrame& DepthOdometry::addTracked(TrackedFrame t) {
  checkNext(t.frame.timestamp, true);
  OdometryFrame& f = t.frame;
  const bool session_start = frames_.empty() || session_pending_;
  const std::size_t index = frames_.size();
  const std::size_t first = session_start ? index : session_starts_.back();
  // Its own odometry's number of this session's first frame.
  const std::size_t offset = session_start ? f.index : replay_offset_;
  const std::string what = "odometry: frame " + std::to_string(index) + " (tracked elsewhere as frame " +
                           std::to_string(f.index) + ")";
  if (f.index < offset || f.index - offset != index - first)
    throw Error(what + ": not the next frame of its session");
  const auto here = [&](std::size_t i) { return i - offset + first; };  // i >= offset
  if (f.reference < offset || f.reference > f.index) throw Error(what + ": its reference is not in its session");
  const bool measured = f.tracked && f.reference != f.index;  // against a reference: a constraint
  if (!f.tracked && f.reference != f.index) throw Error(what + ": not tracked, yet with a reference");
  if (measured != t.constraint.has_value() ||
      (t.constraint && (t.constraint->to != f.index || t.constraint->from != f.reference)))
    throw Error(what + ": its constraint is not the one from its reference to it");
  if (f.keyframe != t.keyframe_view.has_value()) throw Error(what + ": a keyframe comes with its view, and only a keyframe");
  if (f.keyframe && !f.tracked) throw Error(what + ": a keyframe that was not tracked");
  if (measured && !keyframe_view_) throw Error(what + ": tracked before its session's origin");
  // The origin: the session's first tracked frame, a keyframe at T_world_first (as addView() makes it).
  if (f.tracked && !measured &&
      (keyframe_view_ || !f.keyframe || !(f.T_world_camera.matrix() == T_world_first_.matrix())))
    throw Error(what + ": a second origin, or one elsewhere than the session's start");
  if (!f.T_world_camera.matrix().allFinite() ||
      (t.constraint && (t.constraint->loop_closure || !t.constraint->T_from_to.matrix().allFinite() ||
                        !t.constraint->information.allFinite())))
    throw Error(what + ": a pose or constraint that is not the odometry's (not finite, or a loop closure)");
  f.index = index;
  f.reference = here(f.reference);
  f.session = session_start ? session_starts_.size() : frames_.back().session;
  if (t.constraint) {
    t.constraint->from = f.reference;
    t.constraint->to = index;
    constraints_.push_back(*t.constraint);
  }
  if (t.keyframe_view) {
    keyframe_index_ = index;
    keyframe_view_ = std::move(*t.keyframe_view);
    keyframe_edges_.reset();
  }
  previous_view_.reset();
  velocity_.reset();
  keyframe_deskew_.reset();
  if (session_start) {
    session_starts_.push_back(index);
    replay_offset_ = offset;
  }
  session_pending_ = false;
  session_replayed_ = true;
  frames_.push_back(std::move(f));
  return frames_.back();
}

bool DepthOdometry::track(const DepthView& view, const DepthView& ref, std::size_t ref_index, OdometryFrame& f,
                          const char* attempt, const PairParams& pair, const std::optional<Isometry3>& T_ref_predicted,
                          bool* visibility_refused, const std::optional<Isometry3>& T_ref_motion) {
  return take(registerViews(view, ref, pair), ref_index, f, attempt, T_ref_predicted, visibility_refused, T_ref_motion);
}

bool DepthOdometry::take(PairResult r, std::size_t ref_index, OdometryFrame& f, const char* attempt,
                         const std::optional<Isometry3>& T_ref_predicted, bool* visibility_refused,
                         const std::optional<Isometry3>& T_ref_motion) {
  // The free-space check refused a pose, at the default scale or in the finer-scale retry.
  if (visibility_refused && r.visibility_refused) *visibility_refused = true;
  const double dt = f.timestamp - frames_[ref_index].timestamp;
  // A partial pose: its free directions from the motion prediction, taken while the prediction
  // one step ahead of the previous frame is narrow enough; their standard deviation on this edge
  // is the prediction gate's width (scene_change.h) over the time since the reference.
  const bool partial = r.pose.partial && T_ref_motion && !T_ref_predicted;
  std::string why = r.pose.success || partial ? std::string() : r.pose.reason;
  if (r.pose.partial && !partial && !r.pose.success) why = "partial pose not taken: " + r.pose.reason;
  if (partial) {
    why = predictionTooWide(f.timestamp - frames_.back().timestamp, params_.scene_change);
    if (why.empty()) {
      const PredictionGate width = predictionGate(*T_ref_motion, *T_ref_motion, dt, params_.scene_change);
      r.pose.T_target_source = withPrediction(r.pose, *T_ref_motion);
      // (ModelError's bounds: beyond them a standard deviation says nothing more.)
      const Matrix6 prior =
          modelErrorCovariance(ModelError{std::min(width.gate_m, 100.0), std::min(width.gate_deg, 180.0)}).inverse();
      const Matrix6 free = Matrix6::Identity() - observedProjector(r.pose);
      r.edge_information += free.transpose() * prior * free;
    } else {
      why = "partial pose, but " + why;
    }
  }
  if (why.empty()) why = implausibleMotion(r.pose.T_target_source, dt, params_);
  PredictionGate gate;
  if (why.empty() && T_ref_predicted) {
    gate = predictionGate(r.pose.T_target_source, *T_ref_predicted, dt, params_.scene_change);
    if (!gate.within()) why = gate.describe();
  }
  const std::string head = (f.reason.empty() ? "" : "; ") + std::string(attempt) + " frame " + std::to_string(ref_index);
  if (!why.empty()) {
    f.reason += head + ": " + why;
    return false;
  }
  if (T_ref_predicted) {
    char buf[160];
    std::snprintf(buf, sizeof buf, ": taken, %.1f%% and %.1f%% of the overlap violated, seen from both views, ",
                  100.0 * r.visibility.violation_ratio, 100.0 * r.visibility.violation_ratio_lesser);
    f.reason += head + buf + gate.describe();
    f.scene_change = true;
  }
  if (partial) {
    f.partial = true;
    f.free_directions = static_cast<int>(r.pose.unobservable_directions.cols());
    f.reason += head + ": " + r.pose.reason + " (held by the motion prediction)";
  }
  f.tracked = true;
  f.reference = ref_index;
  f.inliers = r.pose.num_inliers;
  f.T_world_camera = frames_[ref_index].T_world_camera * r.pose.T_target_source;
  PoseConstraint c;
  c.from = ref_index;
  c.to = f.index;
  c.T_from_to = r.pose.T_target_source;
  c.information = r.edge_information;
  c.inliers = r.pose.num_inliers;
  c.scene_change = f.scene_change;
  c.free_directions = f.free_directions;
  constraints_.push_back(c);
  return true;
}

void DepthOdometry::checkNext(double timestamp, bool tracked_elsewhere) const {
  if (!std::isfinite(timestamp)) throw Error("odometry: frame " + std::to_string(frames_.size()) + ": timestamp is not finite");
  const bool session_start = frames_.empty() || session_pending_;
  if (!session_start && session_replayed_ != tracked_elsewhere)
    throw Error("odometry: frame " + std::to_string(frames_.size()) + ": its session's frames were " +
                (session_replayed_ ? "tracked elsewhere (addTracked()): none is left here to track it against"
                                   : "tracked here: a frame tracked elsewhere cannot join them"));
  if (!session_start && !(timestamp > frames_.back().timestamp)) {
    char buf[200];
    std::snprintf(buf, sizeof buf, "odometry: frame %zu: timestamp %.6f is not later than the previous frame's (%.6f)",
                  frames_.size(), timestamp, frames_.back().timestamp);
    throw Error(buf);
  }
}

const OdometryFrame& DepthOdometry::addFrame(double timestamp, const RangeScan& sweep,
                                             std::optional<SegmentedDepth> segmented) {
  checkNext(timestamp, false);
  if (params_.rolling_shutter_readout_s != 0.0)
    throw Error("odometry: frame " + std::to_string(frames_.size()) +
                ": a LiDAR sweep is not deskewed for a rolling shutter (rolling_shutter_readout_s must be 0; "
                "lidarOdometryParams() sets it)");
  // Deskewed with the velocity the keyframe's sweep was deskewed with: both then keep the same
  // residual skew, which the step between them does not see to first order (deskewed with
  // different velocities, the step is off by their difference times the sweep, and the next
  // velocity carries that on). A sweep becoming the keyframe is deskewed again with the step
  // that measured it (addView).
  const auto t_seg = std::chrono::steady_clock::now();
  if (params_.deskew_sweeps && keyframe_deskew_ && sweepTimed(sweep)) {
    DepthView view = makeRangeView(deskewSweep(sweep, *keyframe_deskew_), params_.pair.segment, params_.pair.returns);
    return addView(timestamp, std::move(view), msSince(t_seg), true, &sweep);
  }
  if (segmented) return addView(timestamp, std::move(segmented->view), segmented->ms, false, &sweep);
  DepthView view = makeRangeView(sweep, params_.pair.segment, params_.pair.returns);
  return addView(timestamp, std::move(view), msSince(t_seg), false, &sweep);
}

const OdometryFrame& DepthOdometry::addFrame(double timestamp, const cv::Mat& depth_m,
                                             const CameraIntrinsics& intrinsics,
                                             std::optional<SegmentedDepth> segmented) {
  checkNext(timestamp, false);
  if (depth_m.empty()) throw Error("odometry: frame " + std::to_string(frames_.size()) + ": empty depth image");
  if (depth_m.cols != intrinsics.width || depth_m.rows != intrinsics.height) {
    char buf[200];
    std::snprintf(buf, sizeof buf, "odometry: frame %zu: depth image is %dx%d, its intrinsics are %dx%d", frames_.size(),
                  depth_m.cols, depth_m.rows, intrinsics.width, intrinsics.height);
    throw Error(buf);
  }
  // Deskew with the last step's velocity, then segment.
  const auto t_seg = std::chrono::steady_clock::now();
  if (params_.rolling_shutter_readout_s != 0.0 && velocity_) {
    auto [pinhole, k] = pinholeDepth(depth_m, intrinsics);
    DepthView view = makeDepthView(deskewDepth(pinhole, k, *velocity_, params_.rolling_shutter_readout_s), k,
                                   params_.pair.segment);
    return addView(timestamp, std::move(view), msSince(t_seg), true);
  }
  if (segmented)  // made ahead (view_ahead.h): the same view, already there
    return addView(timestamp, std::move(segmented->view), segmented->ms, false);
  DepthView view = makeDepthView(depth_m, intrinsics, params_.pair.segment);
  return addView(timestamp, std::move(view), msSince(t_seg), false);
}

const OdometryFrame& DepthOdometry::addView(double timestamp, DepthView view, double segmentation_ms, bool deskewed,
                                            const RangeScan* sweep) {
  const bool session_start = frames_.empty() || session_pending_;
  OdometryFrame f;
  f.index = frames_.size();
  f.session = session_start ? session_starts_.size() : frames_.back().session;
  f.timestamp = timestamp;
  f.reference = f.index;
  f.deskewed = deskewed;
  f.segmentation_ms = segmentation_ms;
  f.patches = static_cast<int>(view.segmentation.patches.size());

  const auto t_reg = std::chrono::steady_clock::now();
  bool new_keyframe = false;
  if (!keyframe_view_) {
    // The first frame with patches is the origin; frames before it are not tracked.
    f.T_world_camera = T_world_first_;
    if (f.patches > 0) {
      f.tracked = true;
      new_keyframe = true;
    } else {
      f.reason = "no surface patches to start from";
    }
  } else {
    const std::size_t prev = f.index - 1;
    const double dt = timestamp - frames_[prev].timestamp;
    bool visibility_refused = false;  // by a strict attempt: the scene may have changed
    // The motion model's prediction of this frame (standing still without a velocity), in the
    // keyframe's and the previous frame's frames: the tracking path's start, and, where it is a
    // prediction (below), what holds a partial pose's free directions.
    const Isometry3 T_prev_frame = velocity_ ? stepOf(*velocity_, dt) : Isometry3::Identity();
    const Isometry3 T_key_predicted =
        frames_[keyframe_index_].T_world_camera.inverse() * frames_[prev].T_world_camera * T_prev_frame;
    // Which prediction may hold a partial pose's free directions: a constant-velocity one (the
    // previous step measured), or standing still from the session's first tracked frame (the
    // motion model's initial state). After a frame that was not tracked the velocity is gone, but
    // the motion it measured need not be: standing still there is no prediction, and its error
    // is unbounded.
    bool prediction_holds = velocity_.has_value();
    if (!prediction_holds && frames_[prev].tracked) {
      prediction_holds = true;  // unless a frame of this session was tracked before prev
      for (std::size_t k = session_starts_.empty() ? 0 : session_starts_.back(); k < prev && prediction_holds; ++k)
        prediction_holds = !frames_[k].tracked;
    }
    const std::optional<Isometry3> T_key_motion = prediction_holds ? std::optional(T_key_predicted) : std::nullopt;
    const std::optional<Isometry3> T_prev_motion = prediction_holds ? std::optional(T_prev_frame) : std::nullopt;
    // The tracking path: from the constant-velocity prediction, the cheap stages only, taken when
    // the certificate claims a full pose within the prediction's gate; else the whole pipeline.
    // Only while the prediction's gate lies within the dense rounds' last gate: they then start
    // in the basin they end in, where they are as accurate as from RANSAC's pose.
    if (params_.tracking && velocity_ && params_.pair.refine.dense.rounds > 0 &&
        gateAt(dt, params_.scene_change).first <= params_.pair.refine.dense.gates_m.back()) {
      if (!keyframe_edges_ && params_.pair.refine.edges.enabled)
        keyframe_edges_ = std::make_shared<const EdgeTargets>(*keyframe_view_, params_.pair.refine.edges.terms);
      PairResult t = trackViews(view, *keyframe_view_, T_key_predicted, params_.pair, keyframe_edges_.get());
      const std::string before = f.reason;  // a failed shortcut leaves no reason: the pipeline runs next
      f.tracking_path = t.pose.success &&
                        predictionGate(t.pose.T_target_source, T_key_predicted, dt, params_.scene_change).within() &&
                        take(std::move(t), keyframe_index_, f, "tracking against keyframe");
      if (!f.tracking_path) f.reason = before;
    }
    if (f.tracking_path ||
        track(view, *keyframe_view_, keyframe_index_, f, "against keyframe", params_.pair, std::nullopt,
              &visibility_refused, T_key_motion)) {
      const Isometry3 T_key_frame = frames_[keyframe_index_].T_world_camera.inverse() * f.T_world_camera;
      new_keyframe = translationNorm(T_key_frame) > params_.keyframe_distance_m ||
                     rotationAngle(T_key_frame) * 180.0 / M_PI > params_.keyframe_angle_deg;
    } else if (prev != keyframe_index_ &&
               track(view, *previous_view_, prev, f, "against the previous", params_.pair, std::nullopt,
                     &visibility_refused, T_prev_motion)) {
      new_keyframe = true;  // the keyframe no longer reaches this far
    } else if (params_.scene_change.enabled && velocity_ && visibility_refused) {
      // A velocity exists only when the previous frame was tracked.
      const std::string too_wide = predictionTooWide(dt, params_.scene_change);
      if (!too_wide.empty()) {
        f.reason += "; scene change: " + too_wide;
      } else if (track(view, *previous_view_, prev, f, "scene change: against the previous",
                       sceneChangePairParams(params_.pair, params_.scene_change), stepOf(*velocity_, dt))) {
        new_keyframe = true;  // the scene changed: the old keyframe shows what is no longer there
      }
    }
    if (!f.tracked) {
      // Predicted with the last velocity (standing still without one); the keyframe stays.
      f.T_world_camera = frames_[prev].T_world_camera * (velocity_ ? stepOf(*velocity_, dt) : Isometry3::Identity());
    }
  }
  f.registration_ms = msSince(t_reg);

  // The velocity of this step (both frames tracked), for the next frame's deskew and prediction.
  // Computed first and assigned last, with the keyframe's deskewed view: a throw leaves the state.
  std::optional<CameraTwist> next_velocity = velocity_;
  std::optional<Isometry3> T_p_f_measured;  // the step, when it gave a velocity
  if (!session_start) {
    const OdometryFrame& p = frames_.back();
    const Isometry3 T_p_f = p.T_world_camera.inverse() * f.T_world_camera;
    const double dt = timestamp - p.timestamp;
    // Anything but a measured, plausible step leaves no velocity (a prediction is not a
    // measurement): the next frame is then not deskewed, and stands still if it is lost.
    // A step taken through a scene change keeps the velocity its prediction was gated by: a run
    // of such frames (a person walking through the view) is then held to one constant-velocity
    // prediction, and cannot drift off with what moves in the scene.
    if (f.tracked && p.tracked && implausibleMotion(T_p_f, dt, params_).empty()) {
      if (!f.scene_change) next_velocity = twistBetween(p.T_world_camera, f.T_world_camera, dt), T_p_f_measured = T_p_f;
    } else {
      next_velocity.reset();
    }
  }
  // A sweep becoming the keyframe is deskewed with the step that measured it (its velocity in
  // this frame's axes), or kept as it is without one; the sweeps tracked against it are then
  // deskewed with the same (addFrame).
  std::optional<CameraTwist> next_keyframe_deskew = keyframe_deskew_;
  if (new_keyframe) {
    next_keyframe_deskew.reset();  // unless deskewed below or with the previous keyframe's velocity
    if (sweep && params_.deskew_sweeps && sweepTimed(*sweep) && T_p_f_measured) {
      CameraTwist twist = *next_velocity;
      twist.v_mps = T_p_f_measured->linear().transpose() * twist.v_mps;  // w is the step's own axis
      const auto t_seg = std::chrono::steady_clock::now();
      view = makeRangeView(deskewSweep(*sweep, twist), params_.pair.segment, params_.pair.returns);
      f.segmentation_ms += msSince(t_seg);
      f.deskewed = true;
      f.patches = static_cast<int>(view.segmentation.patches.size());
      next_keyframe_deskew = twist;
    } else if (sweep && f.deskewed) {
      next_keyframe_deskew = keyframe_deskew_;
    }
  }
  velocity_ = next_velocity;
  keyframe_deskew_ = next_keyframe_deskew;

  if (new_keyframe) {
    f.keyframe = true;
    keyframe_index_ = f.index;
    keyframe_view_ = view;
    keyframe_edges_.reset();
  }
  previous_view_ = std::move(view);
  if (session_start) session_starts_.push_back(f.index);
  session_pending_ = false;
  session_replayed_ = false;
  frames_.push_back(std::move(f));
  return frames_.back();
}

Trajectory DepthOdometry::trajectory() const {
  Trajectory t;
  t.reserve(frames_.size());
  for (const OdometryFrame& f : frames_) t.push_back({f.timestamp, f.T_world_camera});
  return t;
}

std::size_t DepthOdometry::trackedCount() const {
  std::size_t n = 0;
  for (const OdometryFrame& f : frames_) n += f.tracked ? 1 : 0;
  return n;
}

std::size_t DepthOdometry::sceneChangeCount() const {
  std::size_t n = 0;
  for (const OdometryFrame& f : frames_) n += f.scene_change ? 1 : 0;
  return n;
}

std::size_t DepthOdometry::keyframeCount() const {
  std::size_t n = 0;
  for (const OdometryFrame& f : frames_) n += f.keyframe ? 1 : 0;
  return n;
}

std::size_t DepthOdometry::componentCount() const {
  std::vector<std::size_t> parent(frames_.size());
  for (std::size_t i = 0; i < parent.size(); ++i) parent[i] = i;
  const auto root = [&parent](std::size_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  std::size_t n = frames_.size();
  for (const PoseConstraint& c : constraints_) {
    const std::size_t a = root(c.from), b = root(c.to);
    if (a != b) parent[b] = a, --n;
  }
  return n;
}

}  // namespace gasp
