// Planes at known poses render to the analytic depth: exactly without noise, within the noise
// model with it.
#include <gtest/gtest.h>

#include <cmath>

#include "gasp/sim/noise_model.h"
#include "gasp/sim/renderer.h"

namespace {

using gasp::Isometry3;

const gasp::CameraIntrinsics kK = gasp::CameraIntrinsics::rosDefault();

/// A single large plane through p0 with normal n (camera frame = world frame, camera at origin).
gasp::sim::Scene planeScene(const Eigen::Vector3d& p0, const Eigen::Vector3d& n) {
  gasp::sim::Scene s;
  s.name = "test_plane";
  Isometry3 T = Isometry3::Identity();
  T.linear() = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), n).toRotationMatrix();
  T.translation() = p0;
  s.add("plane", gasp::sim::Rectangle{50.0, 50.0}, T);
  return s;
}

/// Depth of pixel (u, v) on the plane n.(p - p0) = 0.
double analyticDepth(const Eigen::Vector3d& p0, const Eigen::Vector3d& n, int u, int v) {
  const Eigen::Vector3d d((u - kK.cx) / kK.fx, (v - kK.cy) / kK.fy, 1.0);
  return n.dot(p0) / n.dot(d);
}

struct PlaneCase {
  Eigen::Vector3d p0;
  Eigen::Vector3d n;
};

std::vector<PlaneCase> planes() {
  const double a = 30.0 * EIGEN_PI / 180.0;
  return {{{0, 0, 2.0}, {0, 0, -1}},                                          // fronto-parallel
          {{0.1, -0.2, 2.5}, Eigen::Vector3d(0, -std::sin(a), std::cos(a))},  // tilted 30 deg about x
          {{0, 0, 3.0}, Eigen::Vector3d(std::sin(a), 0.3, -1).normalized()}};  // tilted about x and y
}

}  // namespace

TEST(SimRender, PlanesRenderToAnalyticDepth) {
  for (const auto& pc : planes()) {
    const auto scene = planeScene(pc.p0, pc.n);
    const auto frame = gasp::sim::renderFrame(scene, kK, Isometry3::Identity());
    ASSERT_EQ(frame.depth.type(), CV_32FC1);
    ASSERT_EQ(frame.depth.cols, 640);
    ASSERT_EQ(frame.depth.rows, 480);
    double max_err = 0.0;
    for (int v = 0; v < kK.height; ++v)
      for (int u = 0; u < kK.width; ++u) {
        const double z = analyticDepth(pc.p0, pc.n, u, v);
        max_err = std::max(max_err, std::abs(frame.depth.at<float>(v, u) - z));
        ASSERT_EQ(frame.surface_id.at<std::uint16_t>(v, u), 1);
      }
    EXPECT_LT(max_err, 1e-6 * 4.0);  // float rounding only
    // The normal faces the camera.
    const cv::Vec3f n = frame.normal.at<cv::Vec3f>(240, 320);
    EXPECT_NEAR(std::abs(n[0] * pc.n.x() + n[1] * pc.n.y() + n[2] * pc.n.z()), 1.0, 1e-5);
    EXPECT_LT(n[2], 0.0f);
  }
}

TEST(SimRender, ExactModelKeepsAnalyticDepthAtStoragePrecision) {
  const auto model = gasp::sim::KinectNoiseModel::exact();
  for (const auto& pc : planes()) {
    const auto frame = gasp::sim::renderFrame(planeScene(pc.p0, pc.n), kK, Isometry3::Identity());
    const cv::Mat depth = gasp::sim::sensorDepth(frame, model, kK, 1, 0);
    for (int v = 0; v < kK.height; ++v)
      for (int u = 0; u < kK.width; ++u)
        ASSERT_NEAR(depth.at<float>(v, u), analyticDepth(pc.p0, pc.n, u, v), 0.5 / 5000.0 + 1e-6);
  }
}

TEST(SimRender, NoisyPlanesStayWithinTheNoiseModel) {
  const gasp::sim::KinectNoiseModel model;
  for (const auto& pc : planes()) {
    const auto frame = gasp::sim::renderFrame(planeScene(pc.p0, pc.n), kK, Isometry3::Identity());
    const cv::Mat depth = gasp::sim::sensorDepth(frame, model, kK, 42, 3);
    std::size_t valid = 0, within = 0;
    double sum = 0.0, sum_sq = 0.0, sum_sigma_sq = 0.0;
    for (int v = 0; v < kK.height; ++v)
      for (int u = 0; u < kK.width; ++u) {
        const double zs = depth.at<float>(v, u);
        if (zs <= 0.0) continue;
        const double z = analyticDepth(pc.p0, pc.n, u, v);
        const double err = zs - z;
        const double bound = 4.0 * model.axialSigma(z) + 0.5 * model.quantisationStep(z, kK.fx) +
                             0.5 / 5000.0 + 1e-6;
        ++valid;
        within += std::abs(err) <= bound ? 1 : 0;
        sum += err;
        sum_sq += err * err;
        sum_sigma_sq += model.axialSigma(z) * model.axialSigma(z);
      }
    // A smooth plane well inside range and below the grazing limit: nothing is dropped.
    ASSERT_EQ(valid, static_cast<std::size_t>(kK.width * kK.height));
    EXPECT_GE(static_cast<double>(within) / static_cast<double>(valid), 0.999);
    const double mean = sum / static_cast<double>(valid);
    const double rms = std::sqrt(sum_sq / static_cast<double>(valid));
    const double rms_sigma = std::sqrt(sum_sigma_sq / static_cast<double>(valid));
    EXPECT_LT(std::abs(mean), 1e-3) << "noise must be unbiased";
    EXPECT_GT(rms, 0.5 * rms_sigma) << "noise must be present";
    EXPECT_LT(rms, 3.0 * rms_sigma);
  }
}

TEST(SimRender, NearestSurfaceWinsAndEmptyRaysAreZero) {
  gasp::sim::Scene s;
  s.add("far", gasp::sim::Rectangle{0.5, 0.5}, Isometry3(Eigen::Translation3d(0, 0, 3)));
  s.add("near", gasp::sim::Sphere{0.2}, Isometry3(Eigen::Translation3d(0, 0, 2)));
  const auto f = gasp::sim::renderFrame(s, kK, Isometry3::Identity());
  EXPECT_NEAR(f.depth.at<float>(240, 320), 1.8, 1e-3);  // sphere front at z = 1.8
  EXPECT_EQ(f.surface_id.at<std::uint16_t>(240, 320), 2);
  // u = 390: x = 70.5 / 525 * 3 = 0.40 m on the rectangle, outside the sphere's ~52 px radius.
  EXPECT_NEAR(f.depth.at<float>(240, 390), 3.0, 1e-6);
  EXPECT_EQ(f.surface_id.at<std::uint16_t>(240, 390), 1);
  EXPECT_EQ(f.depth.at<float>(0, 0), 0.0f);
  EXPECT_EQ(f.surface_id.at<std::uint16_t>(0, 0), 0);
}
