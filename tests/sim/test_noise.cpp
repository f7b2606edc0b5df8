// The sensor model: dropouts at grazing angles and depth discontinuities, determinism per seed.
#include <gtest/gtest.h>

#include <cmath>

#include "gasp/core/error.h"
#include "gasp/sim/noise_model.h"
#include "gasp/sim/simulation.h"

namespace {

using gasp::Isometry3;
const gasp::CameraIntrinsics kK = gasp::CameraIntrinsics::rosDefault();

/// A plane through (0, 0, 2) whose normal is tilted by tilt_deg about the camera x axis.
gasp::sim::RenderedFrame tiltedPlane(double tilt_deg) {
  gasp::sim::Scene s;
  Isometry3 T = Isometry3::Identity();
  T.linear() = Eigen::AngleAxisd(tilt_deg * EIGEN_PI / 180.0, Eigen::Vector3d::UnitX()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(0, 0, 2);
  s.add("plane", gasp::sim::Rectangle{100.0, 100.0}, T);
  return gasp::sim::renderFrame(s, kK, Isometry3::Identity());
}

int countNonZeroRow(const cv::Mat& m, int v) { return cv::countNonZero(m.row(v)); }

}  // namespace

TEST(SimNoise, SigmaAndQuantisationFollowTheFormulas) {
  const gasp::sim::KinectNoiseModel m;
  EXPECT_NEAR(m.axialSigma(0.4), 0.0012, 1e-12);
  EXPECT_NEAR(m.axialSigma(2.4), 0.0012 + 0.0019 * 4.0, 1e-12);
  EXPECT_NEAR(m.quantisationStep(2.0, 525.0), 4.0 * 0.125 / (525.0 * 0.075), 1e-12);
  EXPECT_NO_THROW(m.validate());
  auto bad = m;
  bad.min_range_m = 7.0;
  EXPECT_THROW(bad.validate(), gasp::Error);
}

TEST(SimNoise, GrazingAnglesAreDropped) {
  auto model = gasp::sim::KinectNoiseModel::exact();
  model.drop_grazing = true;  // only the grazing rule
  // Tilted by 80 deg: on the centre row every ray meets the normal at >= 80 deg > 75 deg.
  const cv::Mat steep = gasp::sim::dropoutMask(tiltedPlane(80.0), model, kK);
  EXPECT_EQ(countNonZeroRow(steep, 240), kK.width);
  // Tilted by 60 deg: on the centre row the angle is <= 60 deg / at most ~63 deg at the corners.
  const cv::Mat moderate = gasp::sim::dropoutMask(tiltedPlane(60.0), model, kK);
  EXPECT_EQ(countNonZeroRow(moderate, 240), 0);
  // The default model drops them too (the sensor depth is 0 there).
  const cv::Mat depth = gasp::sim::sensorDepth(tiltedPlane(80.0), gasp::sim::KinectNoiseModel{}, kK, 1, 0);
  EXPECT_EQ(countNonZeroRow(depth, 240), 0);
}

TEST(SimNoise, DepthDiscontinuitiesAreDropped) {
  gasp::sim::Scene s;
  s.add("wall", gasp::sim::Rectangle{10.0, 10.0}, Isometry3(Eigen::Translation3d(0, 0, 3.0)));
  s.add("box", gasp::sim::Box{Eigen::Vector3d(0.2, 0.2, 0.2)}, Isometry3(Eigen::Translation3d(0, 0, 1.5)));
  const auto frame = gasp::sim::renderFrame(s, kK, Isometry3::Identity());
  auto model = gasp::sim::KinectNoiseModel::exact();
  model.drop_discontinuities = true;  // only the discontinuity rule
  const cv::Mat mask = gasp::sim::dropoutMask(frame, model, kK);
  const int v = 240;
  std::vector<int> edges;
  for (int u = 0; u + 1 < kK.width; ++u)
    if (frame.surface_id.at<std::uint16_t>(v, u) != frame.surface_id.at<std::uint16_t>(v, u + 1))
      edges.push_back(u);
  ASSERT_EQ(edges.size(), 2u);  // wall -> box front -> wall
  for (int e : edges) {
    EXPECT_EQ(mask.at<std::uint8_t>(v, e), 255);
    EXPECT_EQ(mask.at<std::uint8_t>(v, e + 1), 255);
  }
  for (int u = 0; u < kK.width; ++u) {
    bool near_edge = false;
    for (int e : edges) near_edge = near_edge || std::abs(u - e) <= 1 || std::abs(u - e - 1) <= 1;
    if (!near_edge) {
      EXPECT_EQ(mask.at<std::uint8_t>(v, u), 0) << "u = " << u;
    }
  }
  // The dropped band is one pixel on each side of each edge.
  EXPECT_EQ(countNonZeroRow(mask, v), 4);
}

TEST(SimNoise, RangeLimits) {
  gasp::sim::Scene s;
  s.add("near", gasp::sim::Rectangle{10.0, 10.0}, Isometry3(Eigen::Translation3d(0, 0, 0.3)));
  const auto frame = gasp::sim::renderFrame(s, kK, Isometry3::Identity());
  EXPECT_EQ(cv::countNonZero(gasp::sim::dropoutMask(frame, gasp::sim::KinectNoiseModel::exact(), kK)),
            kK.width * kK.height);
}

TEST(SimNoise, SameSeedSameFramesDifferentSeedDifferentNoise) {
  gasp::sim::SimulationOptions o;
  o.frames = 8;
  o.seed = 7;
  const gasp::sim::Simulation a(o);
  const gasp::sim::Simulation b(o);
  // b generates frames in another order: each frame depends only on (seed, index).
  const auto b5 = b.frame(5);
  const auto b3 = b.frame(3);
  const auto a3 = a.frame(3);
  const auto a5 = a.frame(5);
  EXPECT_EQ(cv::norm(a3.depth, b3.depth, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(a5.depth, b5.depth, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(a3.labels, b3.labels, cv::NORM_INF), 0.0);
  EXPECT_GT(cv::countNonZero(a3.depth), kK.width * kK.height / 2);

  o.seed = 8;
  const auto c3 = gasp::sim::Simulation(o).frame(3);
  const cv::Mat differ = c3.depth != a3.depth;
  EXPECT_GT(cv::countNonZero(differ), cv::countNonZero(a3.depth) / 10);
  // The noise does not move which pixels are valid or their labels.
  EXPECT_EQ(cv::norm(a3.labels, c3.labels, cv::NORM_INF), 0.0);
  EXPECT_NE(gasp::sim::frameSeed(7, 3), gasp::sim::frameSeed(7, 4));
  EXPECT_NE(gasp::sim::frameSeed(7, 3), gasp::sim::frameSeed(8, 3));
}

// The systematic radial depth error: z (1 + K rho^2), none at the principal point, the most in
// the corners, the same in every frame; out of [-0.2, 0.2] it is refused.
TEST(SimNoise, RadialDepthBiasBendsAPlaneIntoABowl) {
  auto model = gasp::sim::KinectNoiseModel::exact();
  model.radial_depth_bias = 0.01;
  const auto frame = tiltedPlane(0.0);  // z = 2 m everywhere
  const cv::Mat depth = gasp::sim::sensorDepth(frame, model, kK, 1, 0);
  const double rho2_corner = std::pow((0 - kK.cx) / kK.fx, 2) + std::pow((0 - kK.cy) / kK.fy, 2);
  EXPECT_NEAR(depth.at<float>(0, 0), 2.0 * (1.0 + 0.01 * rho2_corner), 2e-4);
  EXPECT_NEAR(depth.at<float>(240, 320), 2.0, 2e-4);
  EXPECT_GT(depth.at<float>(0, 0) - depth.at<float>(240, 320), 0.01);  // 1.1 cm deeper in the corner
  const cv::Mat again = gasp::sim::sensorDepth(frame, model, kK, 7, 3);
  EXPECT_EQ(cv::norm(depth, again, cv::NORM_INF), 0.0);  // not random
  EXPECT_NO_THROW(model.validate());
  model.radial_depth_bias = 0.3;
  EXPECT_THROW(model.validate(), gasp::Error);
  model.radial_depth_bias = std::nan("");
  EXPECT_THROW(model.validate(), gasp::Error);
}
