#pragma once
/// \file lidar.h A spinning LiDAR in the simulator: its lasers' elevations, its azimuth step and
/// its noise, and a sweep rendered from one pose as a RangeScan (gasp/core/range_scan.h).
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "gasp/core/pose.h"
#include "gasp/core/range_scan.h"
#include "gasp/sim/scene.h"

namespace gasp::sim {

struct LidarSensor {
  std::string model;                  ///< RangeScan::model
  std::vector<double> elevation_deg;  ///< per laser, in laser-id order
  double azimuth_step_deg = 0.2;      ///< between firings (a 10 Hz sweep)
  double min_range_m = 0.5;           ///< nearer returns are dropped
  double max_range_m = 100.0;         ///< farther returns are dropped
  double range_sigma_m = 0.02;        ///< Gaussian range noise (1 sigma)
  double dropout = 0.02;              ///< share of returns lost at random
  double sweep_s = 0.1;               ///< one turn
};

/// The sensors of `gasp-simulate --sensor lidar16|lidar32|lidar64`: 16 lasers as a VLP-16, 32 as
/// an HDL-32E (their tables, laserElevationsDeg()), 64 spread evenly over -24.9..+2 deg (an
/// HDL-64E's field); 0.2 deg azimuth step. Throws gasp::Error for another count.
LidarSensor lidarSensor(int lasers);

/// The LiDAR's pose on a camera's path: its x along the camera's optical axis (z), its y along the
/// image's left (-x), its z up the image (-y); the same origin.
Isometry3 lidarPoseOfCamera(const Isometry3& T_world_camera);

/// One sweep of `sensor` at T_world_sensor (the sensor's x ahead, z up; the sweep turns clockwise
/// from x, as a Velodyne's), with its noise: deterministic in (seed, frame_index). Rows by
/// elevation, as RangeScan orders them. Throws gasp::Error for a sensor without lasers, a step
/// that is not in (0, 360], or a range, noise or dropout out of its domain.
RangeScan simulateLidarScan(const Scene& scene, const LidarSensor& sensor, const Isometry3& T_world_sensor,
                            std::uint64_t seed = 1, int frame_index = 0);

/// One sweep taken while the sensor moves: column c is fired from T_world_sensor_at(t), t its time
/// after the sweep's start (columnTime(), gasp/core/range_scan.h: the columns turn once in
/// sensor.sweep_s), as a real spinning LiDAR's sweep is skewed by its motion. The same noise as
/// simulateLidarScan() for the same (seed, frame_index). Throws as it does, and for an empty
/// function.
RangeScan simulateMovingLidarScan(const Scene& scene, const LidarSensor& sensor,
                                  const std::function<Isometry3(double)>& T_world_sensor_at, std::uint64_t seed = 1,
                                  int frame_index = 0);

}  // namespace gasp::sim
