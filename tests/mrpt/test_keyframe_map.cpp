// The keyframe map (gasp/mrpt/keyframe_map.h): keyframes' scans at their poses as an MRPT simple
// map, and a deskewed keyframe taking its registered view's depth.
#include <gtest/gtest.h>

#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/math/wrap2pi.h>
#include <mrpt/poses/CPose3DPDF.h>
#include <mrpt/poses/CPose3DPDFGaussian.h>

#include <Eigen/Cholesky>

#include <cmath>
#include <limits>
#include <random>

#include "gasp/core/error.h"
#include "gasp/core/pose.h"
#include "gasp/core/pose_perturbation.h"
#include "gasp/mrpt/keyframe_map.h"
#include "gasp/rawlog/frame_convention.h"
#include "gasp/rawlog/observation_conversion.h"

using namespace gasp;

namespace {

/// A 8x6 frame with raw TUM depth (5000 units per metre), distorted intrinsics and a colour image.
RgbdFrame recordedFrame() {
  RgbdFrame f;
  f.timestamp = 12.5;
  f.sensor_label = "KINECT";
  f.depth_intrinsics.width = 8;
  f.depth_intrinsics.height = 6;
  f.depth_intrinsics.fx = f.depth_intrinsics.fy = 7.0;
  f.depth_intrinsics.cx = 3.5;
  f.depth_intrinsics.cy = 2.5;
  f.depth_intrinsics.distortion = {0.26, -0.95, 0.0, 0.0, 1.16};
  f.depth_raw = cv::Mat(6, 8, CV_16UC1, cv::Scalar(7500));  // 1.5 m
  f.depth_units_per_metre = 5000.0;
  f.depth_m = cv::Mat(6, 8, CV_32FC1, cv::Scalar(1.5f));
  f.rgb = cv::Mat(6, 8, CV_8UC3, cv::Scalar(10, 20, 30));
  f.rgb_intrinsics = f.depth_intrinsics;
  f.T_robot_camera = mrptCameraFromOptical();
  return f;
}

/// The view the odometry registered: pinhole intrinsics, deskewed depth (a ramp and one hole).
DepthView registeredView() {
  DepthView v;
  CameraIntrinsics k;
  k.width = 8;
  k.height = 6;
  k.fx = k.fy = 7.2;
  k.cx = 3.4;
  k.cy = 2.6;
  v.projection = k;
  v.depth_m = cv::Mat(6, 8, CV_32FC1);
  for (int r = 0; r < 6; ++r)
    for (int c = 0; c < 8; ++c) v.depth_m.at<float>(r, c) = 1.4f + 0.01234f * static_cast<float>(r * 8 + c);
  v.depth_m.at<float>(2, 3) = std::numeric_limits<float>::quiet_NaN();
  return v;
}

}  // namespace

TEST(KeyframeMap, HoldsEachKeyframesScanAtItsRobotPose) {
  const RgbdFrame f = recordedFrame();
  Isometry3 T_world_camera = Isometry3::Identity();
  T_world_camera.translation() << 0.3, -0.2, 1.0;
  T_world_camera.linear() = Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitY()).toRotationMatrix();
  const mrpt::maps::CSimpleMap map = keyframeSimpleMap({f, f}, {Isometry3::Identity(), T_world_camera});
  ASSERT_EQ(map.size(), 2u);
  const auto [pdf, sf] = map.get(1);
  mrpt::poses::CPose3D mean;
  pdf->getMean(mean);
  const Isometry3 expected = T_world_camera * f.T_robot_camera.inverse();
  EXPECT_LT((fromCPose3D(mean).matrix() - expected.matrix()).norm(), 1e-9);
  const auto scan = sf->getObservationByClass<mrpt::obs::CObservation3DRangeScan>();
  ASSERT_TRUE(scan);
  EXPECT_EQ(scan->rangeImage(0, 0), 7500);  // raw values kept
  EXPECT_FLOAT_EQ(scan->rangeUnits, 1.0f / 5000.0f);
  EXPECT_TRUE(scan->hasIntensityImage);

  EXPECT_THROW(keyframeSimpleMap({f}, {}), Error);
}

TEST(KeyframeMap, EachPoseCarriesTheCameraPosesCovarianceInMrptsTerms) {
  const RgbdFrame f = recordedFrame();
  Isometry3 T_world_camera = Isometry3::Identity();
  T_world_camera.translation() << 2.0, -1.0, 0.5;
  T_world_camera.linear() = (Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(-0.3, Eigen::Vector3d::UnitX()))
                                .toRotationMatrix();
  // A correlated covariance of the camera's left perturbation [t r]: about 1 cm and 0.5 deg.
  Matrix6 B;
  std::mt19937 rng(7);
  std::normal_distribution<double> n(0.0, 1.0);
  for (int r = 0; r < 6; ++r)
    for (int c = 0; c < 6; ++c) B(r, c) = 0.5 * n(rng);
  Vector6 sigma;
  sigma << 0.01, 0.02, 0.005, 0.008, 0.004, 0.01;
  const Matrix6 C = sigma.asDiagonal() * (Matrix6::Identity() + B * B.transpose()) * sigma.asDiagonal();
  const mrpt::maps::CSimpleMap map = keyframeSimpleMap({f, f}, {Isometry3::Identity(), T_world_camera}, {Matrix6::Zero(), C});
  const auto gaussian = std::dynamic_pointer_cast<const mrpt::poses::CPose3DPDFGaussian>(std::get<0>(map.get(1)));
  ASSERT_TRUE(gaussian);
  // The robot pose's [x y z yaw pitch roll] when the camera pose moves by xi ~ N(0, C), sampled.
  const Isometry3 T_world_robot = T_world_camera * f.T_robot_camera.inverse();
  const Eigen::LLT<Matrix6> llt(C);
  const mrpt::poses::CPose3D mean = toCPose3D(T_world_robot);
  Matrix6 sampled = Matrix6::Zero();
  const int samples = 20000;
  for (int k = 0; k < samples; ++k) {
    Vector6 z;
    for (int j = 0; j < 6; ++j) z(j) = n(rng);
    const mrpt::poses::CPose3D p = toCPose3D(expLeft(llt.matrixL() * z) * T_world_camera * f.T_robot_camera.inverse());
    Vector6 d;
    d << p.x() - mean.x(), p.y() - mean.y(), p.z() - mean.z(), mrpt::math::wrapToPi(p.yaw() - mean.yaw()),
        mrpt::math::wrapToPi(p.pitch() - mean.pitch()), mrpt::math::wrapToPi(p.roll() - mean.roll());
    sampled += d * d.transpose() / samples;
  }
  for (int r = 0; r < 6; ++r)
    for (int c = 0; c < 6; ++c)
      EXPECT_NEAR(gaussian->cov(r, c), sampled(r, c), 0.05 * std::sqrt(sampled(r, r) * sampled(c, c)))
          << r << "," << c;
  const auto root = std::dynamic_pointer_cast<const mrpt::poses::CPose3DPDFGaussian>(std::get<0>(map.get(0)));
  ASSERT_TRUE(root);
  EXPECT_EQ(root->cov.norm(), 0.0);

  EXPECT_THROW(keyframeSimpleMap({f, f}, {Isometry3::Identity(), T_world_camera}, {C}), Error);  // one too few
  Matrix6 bad = C;
  bad(1, 1) = std::nan("");
  EXPECT_THROW(keyframeSimpleMap({f}, {T_world_camera}, {bad}), Error);
}

TEST(KeyframeMap, ADeskewedKeyframeTakesTheDepthItWasRegisteredWith) {
  const DepthView view = registeredView();
  const RgbdFrame out = withViewDepth(recordedFrame(), view);
  // The view's depth and pinhole intrinsics; raw depth requantised at the frame's units.
  EXPECT_EQ(out.depth_intrinsics.fx, 7.2);
  EXPECT_EQ(out.depth_intrinsics.cx, 3.4);
  for (double k : out.depth_intrinsics.distortion) EXPECT_EQ(k, 0.0);
  ASSERT_TRUE(out.hasRawDepth());
  EXPECT_EQ(out.depth_units_per_metre, 5000.0);
  for (int r = 0; r < 6; ++r)
    for (int c = 0; c < 8; ++c) {
      const float d = view.depth_m.at<float>(r, c);
      const int expected = std::isfinite(d) ? static_cast<int>(std::lround(d * 5000.0)) : 0;
      EXPECT_EQ(out.depth_raw.at<std::uint16_t>(r, c), expected) << r << "," << c;
    }
  EXPECT_FALSE(out.hasRgb());  // the colour image no longer lies on the depth's pixels
  EXPECT_EQ(out.timestamp, 12.5);
  EXPECT_EQ(out.sensor_label, "KINECT");
  EXPECT_LT((out.T_robot_camera.matrix() - mrptCameraFromOptical().matrix()).norm(), 1e-15);
  // The copy is the frame's own: the view is not aliased.
  EXPECT_NE(out.depth_m.data, view.depth_m.data);

  // In the map: the requantised depth, and no distortion in the camera.
  const mrpt::maps::CSimpleMap map = keyframeSimpleMap({out}, {Isometry3::Identity()});
  const auto scan = std::get<1>(map.get(0))->getObservationByClass<mrpt::obs::CObservation3DRangeScan>();
  ASSERT_TRUE(scan);
  EXPECT_EQ(scan->rangeImage(0, 1), static_cast<std::uint16_t>(std::lround((1.4f + 0.01234f) * 5000.0)));
  EXPECT_EQ(scan->rangeImage(2, 3), 0);
  EXPECT_EQ(scan->cameraParams.distortion, mrpt::img::DistortionModel::none);
  EXPECT_FALSE(scan->hasIntensityImage);
}

TEST(KeyframeMap, AFrameWithoutRawDepthGetsNone) {
  RgbdFrame f = recordedFrame();
  f.depth_raw.release();
  f.depth_units_per_metre = 0.0;
  const RgbdFrame out = withViewDepth(f, registeredView());
  EXPECT_FALSE(out.hasRawDepth());
  EXPECT_FLOAT_EQ(out.depth_m.at<float>(0, 1), 1.4f + 0.01234f);
}

TEST(KeyframeMap, AViewWhoseDepthDisagreesWithItsIntrinsicsIsAnError) {
  DepthView wrong_size = registeredView();
  CameraIntrinsics k = wrong_size.projection.pinhole();
  k.width = 9;
  wrong_size.projection = k;
  EXPECT_THROW(withViewDepth(recordedFrame(), wrong_size), Error);
  DepthView wrong_type = registeredView();
  wrong_type.depth_m.convertTo(wrong_type.depth_m, CV_64FC1);
  EXPECT_THROW(withViewDepth(recordedFrame(), wrong_type), Error);
  DepthView empty;
  EXPECT_THROW(withViewDepth(recordedFrame(), empty), Error);
}
