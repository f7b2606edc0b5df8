// The simulated spinning LiDAR (gasp/sim/lidar.h): its sensors, exact ranges against a plane,
// and its noise.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "gasp/core/error.h"
#include "gasp/sim/lidar.h"
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
