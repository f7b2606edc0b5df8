// Turned images and the rolled camera that would have taken them: every pixel's 3D point, seen by
// the turned camera, is the original point rotated by turnRotation().
#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include <cmath>
#include <utility>

#include "gasp/core/camera_roll.h"
#include "gasp/core/error.h"

namespace {

gasp::CameraIntrinsics offCentreCamera() {
  gasp::CameraIntrinsics K;
  K.width = 64, K.height = 48;
  K.fx = 50.0, K.fy = 47.0;  // unequal, so a swap is seen
  K.cx = 30.2, K.cy = 20.7;  // off centre, so a misplaced principal point is seen
  return K;
}

}  // namespace

TEST(CameraRoll, TurnedPixelsUnprojectToTheRotatedPoints) {
  const gasp::CameraIntrinsics K = offCentreCamera();
  cv::Mat depth(K.height, K.width, CV_32FC1);
  cv::randu(depth, 0.5, 4.0);
  for (const int deg : {0, 90, 180, 270}) {
    const cv::Mat turned = gasp::turnImage(depth, deg);
    const gasp::CameraIntrinsics Kt = gasp::turnIntrinsics(K, deg);
    const gasp::Isometry3 T = gasp::turnRotation(deg);
    ASSERT_EQ(turned.cols, Kt.width) << deg;
    ASSERT_EQ(turned.rows, Kt.height) << deg;
    EXPECT_TRUE(T.linear().isUnitary(1e-12) && T.linear().determinant() > 0.0) << deg;
    EXPECT_EQ(T.translation().norm(), 0.0) << deg;
    // Every turned pixel holds the depth of some original pixel; their points agree through T.
    for (int v = 0; v < turned.rows; ++v) {
      for (int u = 0; u < turned.cols; ++u) {
        const double z = turned.at<float>(v, u);
        const Eigen::Vector3d p_turned = Kt.unproject(u, v, z);
        const Eigen::Vector3d p = T.inverse() * p_turned;
        double u0 = 0.0, v0 = 0.0;
        ASSERT_TRUE(K.project(p, u0, v0));
        const int iu = static_cast<int>(std::lround(u0)), iv = static_cast<int>(std::lround(v0));
        ASSERT_NEAR(u0, iu, 1e-9) << deg << " at " << u << "," << v;
        ASSERT_NEAR(v0, iv, 1e-9) << deg << " at " << u << "," << v;
        ASSERT_EQ(depth.at<float>(iv, iu), turned.at<float>(v, u)) << deg << " at " << u << "," << v;
      }
    }
  }
}

TEST(CameraRoll, TwoHalfTurnsAndFourQuarterTurnsGiveTheOriginal) {
  const gasp::CameraIntrinsics K = offCentreCamera();
  for (const auto& [deg, times] : {std::pair{180, 2}, {90, 4}, {270, 4}}) {
    gasp::CameraIntrinsics k = K;
    for (int i = 0; i < times; ++i) k = gasp::turnIntrinsics(k, deg);
    EXPECT_NEAR(k.cx, K.cx, 1e-12) << deg;
    EXPECT_NEAR(k.cy, K.cy, 1e-12) << deg;
    EXPECT_EQ(k.fx, K.fx) << deg;
    EXPECT_EQ(k.fy, K.fy) << deg;
    EXPECT_EQ(k.width, K.width) << deg;
    EXPECT_EQ(k.height, K.height) << deg;
  }
  EXPECT_TRUE((gasp::turnRotation(90) * gasp::turnRotation(270)).isApprox(gasp::Isometry3::Identity(), 1e-15));
  EXPECT_TRUE((gasp::turnRotation(180) * gasp::turnRotation(180)).isApprox(gasp::Isometry3::Identity(), 1e-15));
}

TEST(CameraRoll, RefusesOtherAnglesAndDistortedLenses) {
  const gasp::CameraIntrinsics K = offCentreCamera();
  EXPECT_THROW(gasp::turnImage(cv::Mat::zeros(4, 4, CV_32FC1), 45), gasp::Error);
  EXPECT_THROW(gasp::turnIntrinsics(K, -90), gasp::Error);
  EXPECT_THROW(gasp::turnRotation(360), gasp::Error);
  gasp::CameraIntrinsics distorted = K;
  distorted.distortion[0] = 0.2;
  EXPECT_THROW(gasp::turnIntrinsics(distorted, 180), gasp::Error);
  EXPECT_NO_THROW(gasp::turnIntrinsics(distorted, 0));
}
