// The simulated spinning LiDAR (gasp/sim/lidar.h): its sensors, exact ranges against a plane,
// and its noise.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "gasp/core/error.h"
#include "gasp/core/range_scan.h"
#include "gasp/core/rolling_shutter.h"
#include "gasp/sim/lidar.h"
#include "gasp/sim/renderer.h"
#include "gasp/sim/scene.h"

namespace {

/// The plane scene's plane (x = 3 m), seen from the origin: the exact range of a ray.
double planeRange(const gasp::RangeScan& s, int row, int col) {
  const double forward = s.direction(row, col).x();
  return forward > 0.2 ? 3.0 / forward : 0.0;
}

}  // namespace

TEST(SimLidar, TheSensorsHaveTheirLasersAndSteps) {
  EXPECT_EQ(gasp::sim::lidarSensor(16).model, "VLP-16");
  EXPECT_EQ(gasp::sim::lidarSensor(32).elevation_deg.size(), 32u);
  const auto s64 = gasp::sim::lidarSensor(64);
  ASSERT_EQ(s64.elevation_deg.size(), 64u);
  EXPECT_NEAR(s64.elevation_deg.front(), -24.9, 1e-9);
  EXPECT_NEAR(s64.elevation_deg.back(), 2.0, 1e-9);
  EXPECT_THROW(gasp::sim::lidarSensor(8), gasp::Error);
}

TEST(SimLidar, ExactRangesOnAPlaneAndNothingBehindIt) {
  const gasp::sim::Scene plane = gasp::sim::makeScene("plane");
  gasp::sim::LidarSensor sensor = gasp::sim::lidarSensor(16);
  sensor.range_sigma_m = 0.0;
  sensor.dropout = 0.0;
  const gasp::RangeScan s = gasp::sim::simulateLidarScan(plane, sensor, gasp::Isometry3::Identity());
  ASSERT_EQ(s.range_m.rows, 16);
  ASSERT_EQ(s.range_m.cols, 1800);
  for (int r = 1; r < 16; ++r) EXPECT_LT(s.elevation_rad[static_cast<std::size_t>(r - 1)], s.elevation_rad[static_cast<std::size_t>(r)]);
  // Clockwise from x: the second column looks 0.2 deg to the right (towards -y).
  EXPECT_LT(s.direction(8, 1).y(), 0.0);
  int hits = 0;
  for (int r = 0; r < 16; ++r)
    for (int c = 0; c < 1800; ++c) {
      const double expected = planeRange(s, r, c);
      const double got = s.range_m.at<float>(r, c);
      if (expected > 0.0) {
        // Within the 40 x 40 m plane (its half extents 20 m): then an exact hit (float).
        const Eigen::Vector3d p = expected * s.direction(r, c);
        if (std::abs(p.y()) < 19.0 && std::abs(p.z()) < 19.0) {
          EXPECT_NEAR(got, expected, 1e-4 * expected) << r << ", " << c;
          ++hits;
        }
      } else if (s.direction(r, c).x() <= 0.0) {
        EXPECT_EQ(got, 0.0f) << r << ", " << c;  // behind the sensor: nothing
      }
    }
  EXPECT_GT(hits, 16 * 700);
  EXPECT_EQ(s.points().size(), s.returnCount());
}

TEST(SimLidar, NoiseAndDropoutsAsAskedAndTheSameForTheSameSeed) {
  const gasp::sim::Scene room = gasp::sim::makeScene("room");
  gasp::sim::LidarSensor exact = gasp::sim::lidarSensor(16);
  exact.range_sigma_m = 0.0;
  exact.dropout = 0.0;
  gasp::sim::LidarSensor noisy = gasp::sim::lidarSensor(16);
  noisy.range_sigma_m = 0.02;
  noisy.dropout = 0.05;
  gasp::Isometry3 T = gasp::Isometry3::Identity();
  T.translation() = Eigen::Vector3d(0.5, 0.0, 1.0);  // inside the room: every ray hits a wall, floor or ceiling
  const gasp::RangeScan truth = gasp::sim::simulateLidarScan(room, exact, T);
  const gasp::RangeScan a = gasp::sim::simulateLidarScan(room, noisy, T, 7, 3);
  const gasp::RangeScan b = gasp::sim::simulateLidarScan(room, noisy, T, 7, 3);
  EXPECT_EQ(cv::norm(a.range_m, b.range_m, cv::NORM_INF), 0.0);
  EXPECT_EQ(truth.returnCount(), static_cast<std::size_t>(16 * 1800));
  double sum = 0.0, sum_sq = 0.0;
  std::size_t kept = 0;
  for (int r = 0; r < 16; ++r)
    for (int c = 0; c < 1800; ++c) {
      const float got = a.range_m.at<float>(r, c);
      if (got <= 0.0f) continue;
      const double e = got - truth.range_m.at<float>(r, c);
      sum += e, sum_sq += e * e, ++kept;
    }
  const double n = static_cast<double>(16 * 1800);
  EXPECT_NEAR(1.0 - static_cast<double>(kept) / n, 0.05, 0.01);  // dropouts
  EXPECT_NEAR(sum / static_cast<double>(kept), 0.0, 0.002);
  EXPECT_NEAR(std::sqrt(sum_sq / static_cast<double>(kept)), 0.02, 0.002);
  EXPECT_GT(cv::norm(a.range_m, gasp::sim::simulateLidarScan(room, noisy, T, 8, 3).range_m, cv::NORM_INF), 0.0);
  noisy.dropout = 1.0;
  EXPECT_THROW(gasp::sim::simulateLidarScan(room, noisy, T), gasp::Error);
}

namespace {

/// The share of `scan`'s returns that lie, within tol_m, where the ray through them from
/// T_world_sensor first meets the scene (the scene rendered along the scan's own rays).
double shareOnTheScene(const gasp::sim::Scene& scene, const gasp::RangeScan& scan, const gasp::Isometry3& T_world_sensor,
                       double tol_m) {
  gasp::RangeScan layout = scan;
  if (layout.ray.empty()) layout.ray = cv::Mat(scan.range_m.rows, scan.range_m.cols, CV_32FC3, cv::Scalar(0.0f, 0.0f, 0.0f));
  const gasp::sim::RenderedScan truth = gasp::sim::renderRangeScan(scene, layout, T_world_sensor);
  int returns = 0, on = 0;
  for (int r = 0; r < scan.range_m.rows; ++r)
    for (int c = 0; c < scan.range_m.cols; ++c)
      if (const float d = scan.range_m.at<float>(r, c); d > 0.0f)
        ++returns, on += std::abs(static_cast<double>(d) - truth.range.at<float>(r, c)) <= tol_m ? 1 : 0;
  return returns > 0 ? static_cast<double>(on) / returns : 0.0;
}

}  // namespace

// A sweep fired while the sensor moves is skewed: many returns lie off the scene seen from the
// sweep's start pose. Carried to that pose with the sensor's twist (deskewSweep), they lie on it
// (each along its own ray, rendered again from the start pose). Two motions over the 0.1 s sweep:
// 1 m/s with a turn of 115 deg/s about the sensor's axis (10 cm, 11.5 deg), and the room path's
// roll, 120 deg/s about the sensor's x (12 deg).
TEST(SimLidar, AMovingSweepDeskewedWithItsTwistLiesOnTheSceneSeenFromItsStart) {
  const gasp::sim::Scene room = gasp::sim::makeScene("room");
  gasp::sim::LidarSensor sensor = gasp::sim::lidarSensor(16);
  sensor.range_sigma_m = 0.0;
  sensor.dropout = 0.0;
  gasp::Isometry3 T_world_start = gasp::Isometry3::Identity();
  T_world_start.translation() = Eigen::Vector3d(0.2, 0.1, 1.3);
  gasp::CameraTwist drive, roll;
  drive.v_mps = Eigen::Vector3d(1.0, 0.3, 0.0);
  drive.w_radps = Eigen::Vector3d(0.1, 0.05, 2.0);
  roll.w_radps = Eigen::Vector3d(120.0 * M_PI / 180.0, 0.0, 0.0);
  for (const gasp::CameraTwist& twist : {drive, roll}) {
    const auto at = [&](double t) { return T_world_start * gasp::twistMotion(twist, t); };
    const gasp::RangeScan moving = gasp::sim::simulateMovingLidarScan(room, sensor, at);
    // Column 0 is fired from the start pose, the last a step short of a turn later.
    EXPECT_DOUBLE_EQ(gasp::columnTime(moving, 0), 0.0);
    EXPECT_NEAR(gasp::columnTime(moving, 1799), 0.1 * 1799.0 / 1800.0, 1e-12);
    ASSERT_TRUE(gasp::sweepTimed(moving));
    const double skewed = shareOnTheScene(room, moving, T_world_start, 0.01);
    const gasp::RangeScan deskewed = gasp::deskewSweep(moving, twist);
    const double on = shareOnTheScene(room, deskewed, T_world_start, 0.01);
    std::printf("within 1 cm of the scene from the start pose: skewed %.3f, deskewed %.4f of %zu returns (%zu before)\n",
                skewed, on, deskewed.returnCount(), moving.returnCount());
    EXPECT_LT(skewed, 0.6);
    EXPECT_GT(on, 0.99);  // the rest: seen from a later pose, hidden from the start's
    // Returns carried beyond half a pitch from the end rows are lost: rolled by up to 12 deg, a
    // 30-deg band of rows loses about an eighth.
    EXPECT_GT(static_cast<double>(deskewed.returnCount()), 0.85 * static_cast<double>(moving.returnCount()));
  }
  // Carried with no motion, the returns stay where they were.
  const gasp::RangeScan still = gasp::sim::simulateLidarScan(room, sensor, T_world_start);
  const gasp::RangeScan same = gasp::deskewSweep(still, gasp::CameraTwist{});
  EXPECT_EQ(same.returnCount(), still.returnCount());
  EXPECT_GT(shareOnTheScene(room, same, T_world_start, 1e-4), 0.999);
  // The columns span the sweep's duration: a half turn of 900 columns in 0.05 s (as MRPT gives a
  // partial span's sweepDuration) fires its middle column at 0.025 s.
  gasp::RangeScan half;
  std::vector<double> azimuths;
  for (int c = 0; c < 900; ++c) azimuths.push_back(-c * 0.2 * M_PI / 180.0);
  half.setLayout(sensor.elevation_deg, azimuths);
  half.sweep_duration_s = 0.05;
  EXPECT_NEAR(gasp::columnTime(half, 450), 0.025, 1e-15);
  // Columns without times are refused, as is a twist that is not finite.
  gasp::RangeScan untimed = still;
  untimed.sweep_duration_s = 0.0;
  EXPECT_FALSE(gasp::sweepTimed(untimed));
  EXPECT_THROW(gasp::deskewSweep(untimed, drive), gasp::Error);
  gasp::CameraTwist bad = drive;
  bad.v_mps.x() = std::nan("");
  EXPECT_THROW(gasp::deskewSweep(still, bad), gasp::Error);
}
