#include "gasp/sim/camera_path.h"

#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "gasp/core/error.h"

namespace gasp::sim {

const TrajectorySegment& CameraPath::segment(const std::string& name) const {
  std::string names;
  for (const auto& s : segments) {
    if (s.name == name) return s;
    names += (names.empty() ? "" : ", ") + s.name;
  }
  throw Error("camera path has no segment '" + name + "'; segments: " + names);
}

Isometry3 lookAt(const Eigen::Vector3d& position, const Eigen::Vector3d& target, double roll_rad,
                 const Eigen::Vector3d& up) {
  const Eigen::Vector3d forward = target - position;
  if (forward.norm() < 1e-9) throw Error("lookAt: target equals the camera position");
  const Eigen::Vector3d z = forward.normalized();
  const Eigen::Vector3d x_raw = z.cross(up);
  if (x_raw.norm() < 1e-9) throw Error("lookAt: viewing direction is parallel to the up vector");
  const Eigen::Vector3d x = x_raw.normalized();
  const Eigen::Vector3d y = z.cross(x);  // points down in the image
  Eigen::Matrix3d R;
  R.col(0) = x;
  R.col(1) = y;
  R.col(2) = z;
  Isometry3 T = Isometry3::Identity();
  T.linear() = R * Eigen::AngleAxisd(roll_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() = position;
  return T;
}

namespace {

struct Waypoint {
  Eigen::Vector3d position;
  Eigen::Vector3d target;
  double roll_deg;
};

}  // namespace

namespace {

/// Throws gasp::Error unless the frames and the rate are ones a path may have.
void checkPathOptions(const CameraPathOptions& options) {
  if (options.frames < kMinPathFrames)
    throw Error("camera path: frames must be at least " + std::to_string(kMinPathFrames) + ", got " +
                std::to_string(options.frames));
  if (options.frames > kMaxPathFrames)
    throw Error("camera path: frames must be at most " + std::to_string(kMaxPathFrames) + ", got " +
                std::to_string(options.frames));
  // Timestamps are written in microseconds: frames must be at least that far apart, and the last
  // stamp must keep them (a double holds about 15 significant digits).
  if (!(std::isfinite(options.rate_hz) && options.rate_hz >= kMinRateHz && options.rate_hz <= kMaxRateHz))
    throw Error("camera path: rate_hz must be between " + std::to_string(kMinRateHz) + " and " +
                std::to_string(kMaxRateHz) + " Hz, got " + std::to_string(options.rate_hz));
  if (!std::isfinite(options.start_time_s))
    throw Error("camera path: start_time_s must be finite");
}

double frameTime(const CameraPathOptions& options, int f) {
  return std::round((options.start_time_s + f / options.rate_hz) * 1e6) / 1e6;
}

}  // namespace

CameraPath makeCameraPath(const CameraPathOptions& options) {
  checkPathOptions(options);

  // Waypoints (world: z up, metres). See scenes.cpp for what is where.
  const std::array<Waypoint, 5> wp{{
      {{-1.0, -0.7, 1.4}, {2.5, 0.3, 0.6}, 0.0},   // start: looking at the table
      {{0.2, 0.6, 1.2}, {2.5, -0.3, 0.6}, 0.0},    // after the wide baseline (1.8 m, ~37 deg yaw)
      {{0.2, 0.4, 1.2}, {1.5, -2.5, 0.8}, 0.0},    // after the pan towards -y (~45 deg)
      {{0.0, 0.0, 1.3}, {2.5, 0.0, 0.7}, 0.0},     // back to the table; the occluder appears
      {{0.0, 0.0, 1.3}, {2.5, 0.0, 0.7}, 180.0},   // rolled by 180 deg about the optical axis
  }};
  const std::array<const char*, 4> names{kWideBaseline, kPartialOverlap, kOccluderAppears, kRoll180};
  const std::array<double, 5> cumulative{0.0, 0.30, 0.55, 0.75, 1.0};

  const int last = options.frames - 1;
  std::array<int, 5> key{};
  for (std::size_t i = 0; i < key.size(); ++i)
    key[i] = static_cast<int>(std::lround(cumulative[i] * last));
  for (std::size_t i = 1; i < key.size(); ++i)  // at least one step per segment
    if (key[i] <= key[i - 1]) key[i] = key[i - 1] + 1;
  key.back() = last;

  CameraPath path;
  for (std::size_t s = 0; s < names.size(); ++s) path.segments.push_back({names[s], key[s], key[s + 1]});

  for (int f = 0; f <= last; ++f) {
    std::size_t s = 0;
    while (s + 1 < names.size() && f > key[s + 1]) ++s;
    const double a = static_cast<double>(f - key[s]) / static_cast<double>(key[s + 1] - key[s]);
    const Waypoint& w0 = wp[s];
    const Waypoint& w1 = wp[s + 1];
    const Eigen::Quaterniond q0(lookAt(w0.position, w0.target).linear());
    const Eigen::Quaterniond q1(lookAt(w1.position, w1.target).linear());
    const double roll = (w0.roll_deg + a * (w1.roll_deg - w0.roll_deg)) * EIGEN_PI / 180.0;
    StampedPose p;
    p.timestamp = frameTime(options, f);
    p.T_world_camera = Isometry3::Identity();
    p.T_world_camera.linear() = (q0.slerp(a, q1).toRotationMatrix() *
                                 Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitZ()).toRotationMatrix());
    p.T_world_camera.translation() = (1.0 - a) * w0.position + a * w1.position;
    path.poses.push_back(p);
  }
  return path;
}

CameraPath makeHandHeldPath(const HandHeldView& view, const CameraPathOptions& options) {
  checkPathOptions(options);
  for (const double v : {view.sweep_m, view.bob_m, view.look_sweep_m, view.roll_deg})
    if (!(std::isfinite(v) && v >= 0.0)) throw Error("hand-held path: amplitudes must be finite and >= 0");
  if (!(std::isfinite(view.period_s) && view.period_s > 0.0)) throw Error("hand-held path: period_s must be > 0");
  if (!view.eye.allFinite() || !view.target.allFinite() || !view.drift_mps.allFinite())
    throw Error("hand-held path: eye, target and drift must be finite");
  // Periods as fractions of the slowest one, pairwise incommensurate; phases spread.
  const double w = 2.0 * EIGEN_PI / view.period_s;
  auto wave = [&](double t, double ratio, double phase) { return std::sin(w * t / ratio + phase); };
  CameraPath path;
  path.segments.push_back({kHandHeld, 0, options.frames - 1});
  for (int f = 0; f < options.frames; ++f) {
    const double t = f / options.rate_hz;
    const Eigen::Vector3d eye = view.eye + view.drift_mps * t +
                                Eigen::Vector3d(view.sweep_m * wave(t, 1.0, 0.0), view.sweep_m * wave(t, 0.77, 0.9),
                                                view.bob_m * wave(t, 0.53, 0.3));
    const Eigen::Vector3d target = view.target + view.drift_mps * t +
                                   Eigen::Vector3d(view.look_sweep_m * wave(t, 0.61, 1.7),
                                                   view.look_sweep_m * wave(t, 0.89, 2.3), 0.0);
    const double roll = view.roll_deg * EIGEN_PI / 180.0 * wave(t, 0.71, 0.5);
    path.poses.push_back({frameTime(options, f), lookAt(eye, target, roll)});
  }
  return path;
}

CameraPath makeWalkPath(const std::vector<WalkWaypoint>& walk, const CameraPathOptions& options) {
  checkPathOptions(options);
  if (walk.size() < 2) throw Error("walk path: needs at least two waypoints");
  const std::size_t legs = walk.size() - 1;
  if (static_cast<std::size_t>(options.frames) < legs + 1)
    throw Error("walk path: " + std::to_string(options.frames) + " frames for " + std::to_string(legs) + " legs");
  std::vector<Eigen::Quaterniond> q;
  for (const WalkWaypoint& w : walk) {
    if (!w.position.allFinite() || !w.target.allFinite()) throw Error("walk path: a waypoint is not finite");
    q.emplace_back(lookAt(w.position, w.target).linear());  // throws when looking along the vertical
  }
  // Each leg's share of the frames by its effort; every leg at least one step.
  std::vector<double> cumulative{0.0};
  for (std::size_t i = 0; i < legs; ++i)
    cumulative.push_back(cumulative.back() + (walk[i + 1].position - walk[i].position).norm() +
                         kWalkMetresPerRadian * q[i].angularDistance(q[i + 1]));
  const int last = options.frames - 1;
  std::vector<int> key;
  for (const double c : cumulative)
    key.push_back(cumulative.back() > 0 ? static_cast<int>(std::lround(c / cumulative.back() * last)) : 0);
  for (std::size_t i = 1; i < key.size(); ++i)
    if (key[i] <= key[i - 1]) key[i] = key[i - 1] + 1;
  for (std::size_t i = key.size() - 1; i > 0 && key[i] > last - static_cast<int>(key.size() - 1 - i); --i)
    key[i] = last - static_cast<int>(key.size() - 1 - i);  // pushed past the end: back from the end
  key.back() = last;

  CameraPath path;
  for (std::size_t i = 0; i < legs; ++i) path.segments.push_back({walk[i].leg, key[i], key[i + 1]});
  for (int f = 0; f <= last; ++f) {
    std::size_t i = 0;
    while (i + 1 < legs && f > key[i + 1]) ++i;
    const double a = static_cast<double>(f - key[i]) / static_cast<double>(key[i + 1] - key[i]);
    StampedPose p;
    p.timestamp = frameTime(options, f);
    p.T_world_camera = Isometry3::Identity();
    p.T_world_camera.linear() = q[i].slerp(a, q[i + 1]).toRotationMatrix();
    p.T_world_camera.translation() = (1.0 - a) * walk[i].position + a * walk[i + 1].position;
    path.poses.push_back(p);
  }
  return path;
}

Isometry3 poseAtTime(const Trajectory& poses, double t) {
  if (poses.size() < 2) throw Error("poseAtTime: a path of " + std::to_string(poses.size()) + " poses (at least 2)");
  if (!std::isfinite(t)) throw Error("poseAtTime: the time is not finite");
  for (std::size_t k = 1; k < poses.size(); ++k)
    if (!(poses[k].timestamp > poses[k - 1].timestamp))
      throw Error("poseAtTime: the poses' timestamps must increase strictly (pose " + std::to_string(k) + ")");
  if (t <= poses.front().timestamp) return poses.front().T_world_camera;
  std::size_t i = 0;
  while (i + 2 < poses.size() && t > poses[i + 1].timestamp) ++i;  // [i, i + 1] holds t, or is the last step
  const StampedPose &a = poses[i], &b = poses[i + 1];
  const double s = (t - a.timestamp) / (b.timestamp - a.timestamp);
  Isometry3 T = Isometry3::Identity();
  T.translation() = (1.0 - s) * a.T_world_camera.translation() + s * b.T_world_camera.translation();
  if (s <= 1.0) {
    const Eigen::Quaterniond qa(a.T_world_camera.linear()), qb(b.T_world_camera.linear());
    T.linear() = qa.slerp(s, qb).toRotationMatrix();
    return T;
  }
  // Past the last pose: the last step's world velocity and turn continued (s > 1 above).
  const Eigen::AngleAxisd turn(a.T_world_camera.linear().transpose() * b.T_world_camera.linear());
  T.linear() = b.T_world_camera.linear() * Eigen::AngleAxisd((s - 1.0) * turn.angle(), turn.axis()).toRotationMatrix();
  return T;
}

}  // namespace gasp::sim
