// Rolling-shutter deskew of depth images (rolling_shutter.h).
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "gasp/core/error.h"
#include "gasp/core/rolling_shutter.h"

namespace {

gasp::CameraIntrinsics camera() {
  gasp::CameraIntrinsics k = gasp::CameraIntrinsics::rosDefault();
  k.width = 320;
  k.height = 240;
  k.fx = k.fy = 262.5;
  k.cx = 159.5;
  k.cy = 119.5;
  return k;
}

const std::vector<std::pair<Eigen::Vector3d, double>>& twoPlanes();

/// Depth [m] of a scene of two planes (a slanted wall z = 2 + 0.3 x, a floor y = 0.6; the frame
/// is the camera's at the stamp) seen by a camera that moves with the given twist; row r is
/// exposed (r / (H-1) - 1/2) * readout_s after the stamp. readout_s = 0: a global shutter.
cv::Mat renderTwoPlanes(const gasp::CameraIntrinsics& k, const gasp::CameraTwist& twist, double readout_s) {
  const auto& planes = twoPlanes();
  cv::Mat depth(k.height, k.width, CV_32FC1, cv::Scalar(0.0f));
  for (int r = 0; r < k.height; ++r) {
    const double dt = (static_cast<double>(r) / (k.height - 1) - 0.5) * readout_s;
    const double w = twist.w_radps.norm();
    const Eigen::Matrix3d R =
        w > 0 ? Eigen::AngleAxisd(w * dt, twist.w_radps / w).toRotationMatrix() : Eigen::Matrix3d::Identity();
    const Eigen::Vector3d origin = twist.v_mps * dt;
    for (int u = 0; u < k.width; ++u) {
      const Eigen::Vector3d ray_row((u - k.cx) / k.fx, (r - k.cy) / k.fy, 1.0);
      const Eigen::Vector3d ray = R * ray_row;
      double best = std::numeric_limits<double>::infinity();
      for (const auto& [n, d] : planes) {
        const double s = (d - n.dot(origin)) / n.dot(ray);
        if (s > 0 && s < best) best = s;
      }
      // Depth in the row's camera frame: the ray's z there is 1 per unit s.
      if (std::isfinite(best)) depth.at<float>(r, u) = static_cast<float>(best);
    }
  }
  return depth;
}

/// The planes of renderTwoPlanes(), n.x = d in the stamp's camera frame.
const std::vector<std::pair<Eigen::Vector3d, double>>& twoPlanes() {
  static const std::vector<std::pair<Eigen::Vector3d, double>> planes = {
      {Eigen::Vector3d(-0.3, 0.0, 1.0), 2.0},
      {Eigen::Vector3d(0.0, 1.0, 0.0), 0.6},
  };
  return planes;
}

/// How well a depth image, back-projected with the pinhole model as one instant, fits the scene:
/// the 95th percentile of the pixels' distance [m] to the nearer plane, and the share of pixels
/// with depth.
std::pair<double, double> planeFit(const cv::Mat& depth, const gasp::CameraIntrinsics& k) {
  std::vector<double> distances;
  for (int r = 0; r < depth.rows; ++r)
    for (int u = 0; u < depth.cols; ++u) {
      const float d = depth.at<float>(r, u);
      if (!(d > 0)) continue;
      const Eigen::Vector3d p = k.unproject(u, r, d);
      double best = std::numeric_limits<double>::infinity();
      for (const auto& [n, offset] : twoPlanes()) best = std::min(best, std::abs(n.dot(p) - offset) / n.norm());
      distances.push_back(best);
    }
  if (distances.empty()) return {std::numeric_limits<double>::infinity(), 0.0};
  const auto k95 = distances.begin() + static_cast<std::ptrdiff_t>(0.95 * static_cast<double>(distances.size()));
  std::nth_element(distances.begin(), k95, distances.end());
  return {*k95, static_cast<double>(distances.size()) / (depth.rows * depth.cols)};
}

gasp::CameraTwist movingCamera() {
  gasp::CameraTwist t;
  t.v_mps = Eigen::Vector3d(0.5, 0.2, 0.4);
  t.w_radps = Eigen::Vector3d(0.3, -0.2, 0.5);
  return t;
}

}  // namespace

TEST(RollingShutter, DeskewPutsThePointsBackOnTheSurfaces) {
  const auto k = camera();
  const auto twist = movingCamera();
  constexpr double kReadout = 0.03;
  const auto [global_p95, global_valid] = planeFit(renderTwoPlanes(k, twist, 0.0), k);
  ASSERT_LT(global_p95, 1e-5);  // the renderer itself
  const cv::Mat rolling = renderTwoPlanes(k, twist, kReadout);
  const auto [skewed_p95, skewed_valid] = planeFit(rolling, k);
  EXPECT_GT(skewed_p95, 0.005) << "the scene must be visibly skewed for this test to mean anything";

  const auto [p95, valid] = planeFit(gasp::deskewDepth(rolling, k, twist, kReadout), k);
  EXPECT_LT(p95, 0.0005) << "skewed " << skewed_p95 << " wrong sign " << planeFit(gasp::deskewDepth(rolling, k, twist, -kReadout), k).first;
  EXPECT_GT(valid, 0.97 * skewed_valid);

  // Reading the rows the other way round makes it worse, not better.
  EXPECT_GT(planeFit(gasp::deskewDepth(rolling, k, twist, -kReadout), k).first, skewed_p95);
  (void)global_valid;
}

TEST(RollingShutter, NoMotionOrNoReadoutLeavesTheImage) {
  const auto k = camera();
  const cv::Mat depth = renderTwoPlanes(k, {}, 0.0);
  EXPECT_EQ(cv::norm(depth, gasp::deskewDepth(depth, k, {}, 0.03), cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(depth, gasp::deskewDepth(depth, k, movingCamera(), 0.0), cv::NORM_INF), 0.0);
}

TEST(RollingShutter, MissingAndNonFiniteDepthStayEmptyAndDoNotGrow) {
  const auto k = camera();
  const cv::Mat whole = renderTwoPlanes(k, {}, 0.0);
  cv::Mat holed = whole.clone();
  holed(cv::Rect(100, 190, 40, 30)).setTo(0.0f);  // low rows: exposed late, shifted most
  holed(cv::Rect(10, 10, 5, 5)).setTo(std::numeric_limits<float>::quiet_NaN());
  holed(cv::Rect(20, 10, 5, 5)).setTo(std::numeric_limits<float>::infinity());
  const cv::Mat out_whole = gasp::deskewDepth(whole, k, movingCamera(), 0.03);
  const cv::Mat out = gasp::deskewDepth(holed, k, movingCamera(), 0.03);
  for (int r = 0; r < out.rows; ++r)
    for (int u = 0; u < out.cols; ++u) ASSERT_TRUE(std::isfinite(out.at<float>(r, u)));
  // The holes move with the image (by a pixel or two here); they are neither filled nor grown
  // by the shift.
  const int extra_holes = cv::countNonZero(out_whole) - cv::countNonZero(out);
  const int hole_area = 40 * 30 + 2 * 5 * 5;
  EXPECT_GE(extra_holes, hole_area * 95 / 100);
  EXPECT_LE(extra_holes, hole_area * 103 / 100);
  EXPECT_EQ(cv::countNonZero(out(cv::Rect(106, 196, 28, 18))), 0);  // the hole's inside stays empty
  EXPECT_EQ(cv::countNonZero(gasp::deskewDepth(cv::Mat::zeros(k.height, k.width, CV_32FC1), k, movingCamera(), 0.03)), 0);
}

TEST(RollingShutter, TwistBetweenTwoPoses) {
  const auto expected = movingCamera();
  constexpr double dt = 0.04;
  gasp::Isometry3 T_world_a = gasp::Isometry3::Identity();
  T_world_a.linear() = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  T_world_a.translation() = Eigen::Vector3d(1.0, -2.0, 0.5);
  gasp::Isometry3 T_a_b = gasp::Isometry3::Identity();
  T_a_b.linear() = Eigen::AngleAxisd(expected.w_radps.norm() * dt, expected.w_radps.normalized()).toRotationMatrix();
  T_a_b.translation() = expected.v_mps * dt;
  const auto twist = gasp::twistBetween(T_world_a, T_world_a * T_a_b, dt);
  EXPECT_LT((twist.v_mps - expected.v_mps).norm(), 1e-9);
  EXPECT_LT((twist.w_radps - expected.w_radps).norm(), 1e-9);
  EXPECT_LT(gasp::twistBetween(T_world_a, T_world_a, dt).w_radps.norm(), 1e-12);

  // The velocity is in the camera's own frame: a camera moving along the world's x axis at
  // 0.5 m/s, rotated 90 deg about z, moves along its own -y axis.
  gasp::Isometry3 T_world_c = gasp::Isometry3::Identity();
  T_world_c.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  gasp::Isometry3 T_world_d = T_world_c;
  T_world_d.translation() += Eigen::Vector3d(0.5 * dt, 0.0, 0.0);
  const auto along = gasp::twistBetween(T_world_c, T_world_d, dt);
  EXPECT_LT((along.v_mps - Eigen::Vector3d(0.0, -0.5, 0.0)).norm(), 1e-9) << along.v_mps.transpose();
  EXPECT_LT(along.w_radps.norm(), 1e-12);
}

TEST(RollingShutter, BadInputThrows) {
  const auto k = camera();
  const cv::Mat depth = renderTwoPlanes(k, {}, 0.0);
  EXPECT_THROW(gasp::deskewDepth(cv::Mat::zeros(k.height, k.width, CV_16UC1), k, {}, 0.03), gasp::Error);
  EXPECT_THROW(gasp::deskewDepth(cv::Mat::zeros(k.height + 1, k.width, CV_32FC1), k, {}, 0.03), gasp::Error);
  EXPECT_THROW(gasp::deskewDepth(cv::Mat(), k, {}, 0.03), gasp::Error);
  auto nan_twist = movingCamera();
  nan_twist.v_mps.x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(gasp::deskewDepth(depth, k, nan_twist, 0.03), gasp::Error);
  EXPECT_THROW(gasp::deskewDepth(depth, k, {}, std::numeric_limits<double>::infinity()), gasp::Error);
  EXPECT_THROW(gasp::twistBetween(gasp::Isometry3::Identity(), gasp::Isometry3::Identity(), 0.0), gasp::Error);
  EXPECT_THROW(gasp::twistBetween(gasp::Isometry3::Identity(), gasp::Isometry3::Identity(), -1.0), gasp::Error);
}
