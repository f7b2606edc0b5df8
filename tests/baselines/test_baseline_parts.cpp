// The baselines' parts on synthetic input: method names, the dense SIFT grid, colour required,
// keypoint sampling on a synthetic box corner, the match picture.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include <cmath>

#include "gasp/baselines/baseline_method.h"
#include "gasp/baselines/baseline_registration.h"
#include "gasp/baselines/dense_sift_features.h"
#include "gasp/baselines/match_picture.h"
#include "gasp/baselines/point_features.h"
#include "gasp/baselines/sift_features.h"
#include "gasp/core/error.h"
#include "gasp/sim/lidar.h"
#include "gasp/sim/scene.h"

namespace gb = gasp::baselines;

namespace {

/// A room corner seen from inside: floor y = 0.6, left wall x = -0.8, back wall z = 2.5 (meters,
/// camera frame); textured colour (a checkerboard in u, v) so that SIFT finds corners.
gb::RgbdImage cornerView() {
  gb::RgbdImage v;
  v.intrinsics = gasp::CameraIntrinsics::rosDefault();
  v.depth_m.create(480, 640, CV_32F);
  v.bgr.create(480, 640, CV_8UC3);
  const auto& K = v.intrinsics;
  for (int r = 0; r < 480; ++r)
    for (int c = 0; c < 640; ++c) {
      const double x = (c - K.cx) / K.fx, y = (r - K.cy) / K.fy;  // ray (x, y, 1)
      double z = 2.5;
      if (y > 0 && 0.6 / y < z) z = 0.6 / y;
      if (x < 0 && -0.8 / x < z) z = -0.8 / x;
      v.depth_m.at<float>(r, c) = static_cast<float>(z);
      const bool dark = ((c / 40) + (r / 40)) % 2 == 0;
      v.bgr.at<cv::Vec3b>(r, c) = dark ? cv::Vec3b(40, 60, 200) : cv::Vec3b(220, 230, 240);
    }
  return v;
}

}  // namespace

TEST(BaselineMethod, NamesRoundTrip) {
  for (auto m : gb::allMethods()) EXPECT_EQ(gb::parseMethod(gb::methodName(m)), m);
  EXPECT_THROW(gb::parseMethod("gasp"), gasp::Error);
  EXPECT_FALSE(gb::needsColour(gb::BaselineMethod::kFpfh));
  EXPECT_FALSE(gb::needsColour(gb::BaselineMethod::kShot));
  EXPECT_TRUE(gb::needsColour(gb::BaselineMethod::kColourShot));
  EXPECT_TRUE(gb::needsColour(gb::BaselineMethod::kSift));
  EXPECT_TRUE(gb::needsColour(gb::BaselineMethod::kDenseSift));
}

TEST(DenseSift, DescribesTheGridAtEveryScale) {
  const auto v = cornerView();
  gb::DenseSiftParams p;
  const auto k = gb::describeDenseSift(v, p);
  // Every grid point has depth and lies on a plane with a normal, except possibly along creases.
  const std::size_t grid = (640 / 8) * (480 / 8) * 3;
  EXPECT_LE(k.size(), grid);
  EXPECT_GE(k.size(), grid * 9 / 10);
  EXPECT_EQ(k.descriptors.rows, static_cast<int>(k.size()));
  EXPECT_EQ(k.descriptors.cols, 128);
  for (const auto& px : k.pixels) {
    EXPECT_FLOAT_EQ(std::fmod(px.x - 4.0f, 8.0f), 0.0f);
    EXPECT_FLOAT_EQ(std::fmod(px.y - 4.0f, 8.0f), 0.0f);
  }
  // 3D points are back-projections of their pixels with the depth there.
  for (std::size_t i = 0; i < k.size(); i += 97) {
    const auto& px = k.pixels[i];
    const float z = v.depth_m.at<float>(static_cast<int>(px.y), static_cast<int>(px.x));
    EXPECT_NEAR((k.points[i] - v.intrinsics.unproject(px.x, px.y, z)).norm(), 0.0, 1e-6);
    EXPECT_NEAR(k.normals[i].norm(), 1.0, 1e-6);
    EXPECT_LT(k.normals[i].dot(k.points[i]), 0.0);  // facing the camera
  }
}

TEST(PointFeatures, SampleEnoughKeypointsWithSurfaceNormals) {
  const auto v = cornerView();
  for (auto type : {gb::PointFeatureType::kFpfh, gb::PointFeatureType::kShot, gb::PointFeatureType::kColourShot}) {
    gb::PointFeatureParams p;
    const auto k = gb::describePointFeatures(v, type, p);
    EXPECT_GE(static_cast<int>(k.size()), p.min_keypoints * 9 / 10);  // a few lose their descriptor at the border
    EXPECT_EQ(k.descriptors.cols, type == gb::PointFeatureType::kFpfh ? 33 : type == gb::PointFeatureType::kShot ? 352 : 1344);
    // The keypoints are on the planes, with the planes' normals.
    int on_floor = 0;
    for (std::size_t i = 0; i < k.size(); ++i) {
      const auto& p3 = k.points[i];
      if (std::abs(p3.y() - 0.6) < 0.005 && p3.x() > -0.7 && p3.z() < 2.4) {
        ++on_floor;
        EXPECT_GT(-k.normals[i].y(), 0.99) << "floor normal " << k.normals[i].transpose();
      }
    }
    EXPECT_GT(on_floor, 200);
  }
}

TEST(Baselines, ColourMethodsNeedColour) {
  auto v = cornerView();
  v.bgr.release();
  EXPECT_THROW(gb::describeSift(v), gasp::Error);
  EXPECT_THROW(gb::describeDenseSift(v), gasp::Error);
  EXPECT_THROW(gb::describePointFeatures(v, gb::PointFeatureType::kColourShot), gasp::Error);
  EXPECT_NO_THROW(gb::describePointFeatures(v, gb::PointFeatureType::kShot));
  EXPECT_THROW(gb::registerWithBaseline(v, v, gb::BaselineMethod::kSift), gasp::Error);
}

TEST(Baselines, EmptyViewGivesNoEstimateWithReason) {
  auto v = cornerView();
  v.depth_m.setTo(0.0f);
  const auto r = gb::registerWithBaseline(v, v, gb::BaselineMethod::kFpfh);
  EXPECT_FALSE(r.pose.success);
  EXPECT_NE(r.pose.reason.find("no matches"), std::string::npos) << r.pose.reason;
}

TEST(Baselines, InvalidParametersThrow) {
  gb::BaselineParams p;
  p.point.fpfh_radius_m = 0.01;  // below the normal radius
  EXPECT_THROW(gb::validate(p), gasp::Error);
  p = {};
  p.dense_sift.scales.clear();
  EXPECT_THROW(gb::validate(p), gasp::Error);
  p = {};
  p.sift.surface.voxel_m = 0;
  EXPECT_THROW(gb::validate(p), gasp::Error);
  EXPECT_FALSE(p.pose.refine == true && false);
  EXPECT_FALSE(gb::BaselineParams{}.pose.refine);  // RANSAC only, as gasp-norefine
}

TEST(MatchPicture, SideBySideWithColouredLines) {
  cv::Mat a(100, 120, CV_8UC3, cv::Scalar(255, 255, 255)), b(80, 100, CV_8UC1, cv::Scalar(255));
  const std::vector<cv::Point2f> ma{{10, 10}}, mb{{20, 20}};
  const cv::Mat pic = gb::drawKeypointMatches(a, b, ma, mb, ma, mb, {0});
  EXPECT_EQ(pic.cols, 220);
  EXPECT_EQ(pic.rows, 100);
  // The line's middle is red (wrong match).
  const cv::Vec3b mid = pic.at<cv::Vec3b>(15, 75);
  EXPECT_GT(mid[2], 200);
  EXPECT_LT(mid[1], 100);
  EXPECT_THROW(gb::drawKeypointMatches(a, b, ma, mb, ma, {}, {}), gasp::Error);
  EXPECT_THROW(gb::drawKeypointMatches(a, b, ma, mb, ma, mb, {1, 1}), gasp::Error);
}

// FPFH + RANSAC on two simulated LiDAR sweeps of the room (registerSweepsWithBaseline): a pose
// near the truth (RANSAC only: no refinement, so within a coarse bound), keypoints without pixels;
// methods that need an image are refused.
TEST(Baselines, FpfhRegistersTwoLidarSweeps) {
  const gasp::sim::Scene room = gasp::sim::makeScene("room");
  gasp::Isometry3 T_world_a = gasp::Isometry3::Identity();
  T_world_a.translation() = Eigen::Vector3d(0.6, 0.0, 1.0);
  gasp::Isometry3 T_world_b = T_world_a;
  T_world_b.translation() += Eigen::Vector3d(0.3, 0.1, 0.0);
  T_world_b.linear() = Eigen::AngleAxisd(20.0 * M_PI / 180.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const gasp::sim::LidarSensor sensor = gasp::sim::lidarSensor(16);
  const gasp::RangeScan a = gasp::sim::simulateLidarScan(room, sensor, T_world_a, 1, 0);
  const gasp::RangeScan b = gasp::sim::simulateLidarScan(room, sensor, T_world_b, 1, 1);
  const gb::BaselineResult r = gb::registerSweepsWithBaseline(a, b, gb::BaselineMethod::kFpfh);
  ASSERT_TRUE(r.pose.success) << r.pose.reason;
  ASSERT_FALSE(r.source.points.empty());
  EXPECT_EQ(r.source.pixels.front().x, -1.0f);
  const gasp::Isometry3 error = (T_world_b.inverse() * T_world_a).inverse() * r.pose.T_target_source;
  EXPECT_LT(error.translation().norm(), 0.2);
  EXPECT_LT(Eigen::AngleAxisd(error.linear()).angle() * 180.0 / M_PI, 5.0);
  EXPECT_THROW(gb::registerSweepsWithBaseline(a, b, gb::BaselineMethod::kSift), gasp::Error);
  EXPECT_THROW(gb::registerSweepsWithBaseline(a, b, gb::BaselineMethod::kColourShot), gasp::Error);
}
