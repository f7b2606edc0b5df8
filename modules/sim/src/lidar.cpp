#include "gasp/sim/lidar.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <utility>
#include <random>

#include "gasp/core/error.h"
#include "gasp/sim/renderer.h"

namespace gasp::sim {

LidarSensor lidarSensor(int lasers) {
  LidarSensor s;
  if (lasers == 16) {
    s.model = "VLP-16";
  } else if (lasers == 32) {
    s.model = "HDL-32E";
  } else if (lasers == 64) {
    s.model = "SIM-64";
  } else {
    throw Error("lidar: " + std::to_string(lasers) + " lasers; the simulated sensors have 16, 32 or 64");
  }
  s.elevation_deg = laserElevationsDeg(s.model, lasers);
  return s;
}

namespace {

/// The sweep's layout (rows, columns, duration) for `sensor`, after checking the sensor.
RangeScan sweepLayout(const LidarSensor& sensor) {
  if (sensor.elevation_deg.empty()) throw Error("lidar '" + sensor.model + "': no lasers");
  if (!(sensor.azimuth_step_deg > 0.0 && sensor.azimuth_step_deg <= 360.0))
    throw Error("lidar '" + sensor.model + "': azimuth_step_deg must be in (0, 360]");
  if (!(sensor.min_range_m >= 0.0 && sensor.max_range_m > sensor.min_range_m) || !(sensor.range_sigma_m >= 0.0) ||
      !(sensor.dropout >= 0.0 && sensor.dropout < 1.0) || !(sensor.sweep_s > 0.0))
    throw Error("lidar '" + sensor.model + "': ranges, noise, dropout or sweep out of their domain");
  RangeScan scan;
  scan.model = sensor.model;
  scan.sweep_duration_s = sensor.sweep_s;
  const int cols = static_cast<int>(std::lround(360.0 / sensor.azimuth_step_deg));
  std::vector<double> azimuths;
  for (int c = 0; c < cols; ++c) azimuths.push_back(-c * sensor.azimuth_step_deg * M_PI / 180.0);
  scan.setLayout(sensor.elevation_deg, std::move(azimuths));
  return scan;
}

/// The sensor's noise and dropouts applied to the true ranges, into `scan` (its layout set).
void measure(const LidarSensor& sensor, const RenderedScan& truth, std::uint64_t seed, int frame_index,
             RangeScan& scan) {
  const int rows = scan.range_m.rows, cols = scan.range_m.cols;
  // The noise: the same for the same (seed, frame), whatever else was simulated.
  std::mt19937_64 rng(seed * 0x9E3779B97F4A7C15ULL + static_cast<std::uint64_t>(frame_index));
  std::normal_distribution<double> noise(0.0, sensor.range_sigma_m);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      const double t = truth.range.at<float>(r, c);
      const double e = sensor.range_sigma_m > 0.0 ? noise(rng) : 0.0;
      const bool lost = uniform(rng) < sensor.dropout;
      if (!(t > 0.0) || lost) continue;
      const double d = t + e;
      if (d >= sensor.min_range_m && d <= sensor.max_range_m) scan.range_m.at<float>(r, c) = static_cast<float>(d);
    }
}

}  // namespace

RangeScan simulateLidarScan(const Scene& scene, const LidarSensor& sensor, const Isometry3& T_world_sensor,
                            std::uint64_t seed, int frame_index) {
  RangeScan scan = sweepLayout(sensor);
  measure(sensor, renderRangeScan(scene, scan, T_world_sensor, frame_index), seed, frame_index, scan);
  return scan;
}

RangeScan simulateMovingLidarScan(const Scene& scene, const LidarSensor& sensor,
                                  const std::function<Isometry3(double)>& T_world_sensor_at, std::uint64_t seed,
                                  int frame_index) {
  if (!T_world_sensor_at) throw Error("lidar '" + sensor.model + "': no pose function");
  RangeScan scan = sweepLayout(sensor);
  const RenderedScan truth = renderMovingRangeScan(
      scene, scan, [&](int col) { return T_world_sensor_at(columnTime(scan, col)); }, frame_index);
  measure(sensor, truth, seed, frame_index, scan);
  return scan;
}

Isometry3 lidarPoseOfCamera(const Isometry3& T_world_camera) {
  Eigen::Matrix3d R_camera_lidar;
  R_camera_lidar.col(0) = Eigen::Vector3d(0, 0, 1);   // ahead: the optical axis
  R_camera_lidar.col(1) = Eigen::Vector3d(-1, 0, 0);  // left: against the image's x
  R_camera_lidar.col(2) = Eigen::Vector3d(0, -1, 0);  // up: against the image's y
  Isometry3 T_camera_lidar = Isometry3::Identity();
  T_camera_lidar.linear() = R_camera_lidar;
  return T_world_camera * T_camera_lidar;
}

}  // namespace gasp::sim
