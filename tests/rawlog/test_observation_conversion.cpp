// RgbdFrame <-> CObservation3DRangeScan, and the MRPT / optical frame convention checked against
// MRPT's own unprojection.
#include <gtest/gtest.h>

#include <opencv2/calib3d.hpp>
#include <mrpt/core/Clock.h>
#include <mrpt/opengl/CPointCloud.h>
#include <mrpt/poses/CPose3D.h>

#include <cmath>
#include <filesystem>

#include "gasp/core/error.h"
#include "gasp/core/point_cloud.h"
#include "gasp/rawlog/frame_convention.h"
#include "gasp/rawlog/observation_conversion.h"
#include "gasp_test_data.h"
#include "rawlog_test_frames.h"

namespace {
constexpr double kDeg = M_PI / 180.0;
}

TEST(FrameConvention, MatchesMrptDefaultIntensityPose) {
  const mrpt::poses::CPose3D mrpt_default(0, 0, 0, -90.0 * kDeg, 0.0, -90.0 * kDeg);
  const gasp::Isometry3 T = gasp::fromCPose3D(mrpt_default);
  EXPECT_TRUE(T.isApprox(gasp::mrptCameraFromOptical(), 1e-12)) << T.matrix();
  // Optical z (forward) is MRPT +X, optical x (right) is MRPT -Y, optical y (down) is MRPT -Z.
  EXPECT_TRUE((gasp::mrptCameraFromOptical() * Eigen::Vector3d(0, 0, 1)).isApprox(Eigen::Vector3d(1, 0, 0)));
  EXPECT_TRUE((gasp::mrptCameraFromOptical() * Eigen::Vector3d(1, 0, 0)).isApprox(Eigen::Vector3d(0, -1, 0)));
  EXPECT_TRUE((gasp::mrptCameraFromOptical() * Eigen::Vector3d(0, 1, 0)).isApprox(Eigen::Vector3d(0, 0, -1)));
  // A default-constructed scan's relativePoseIntensityWRTDepth means "coincident cameras".
  mrpt::obs::CObservation3DRangeScan obs;
  EXPECT_TRUE(obs.doDepthAndIntensityCamerasCoincide());
}

TEST(FrameConvention, MrptUnprojectionEqualsGaspBackProjection) {
  gasp::RgbdFrame f = gasp::test::syntheticFrame(1.5);
  // Sensor on a robot: 0.3 m up, 0.1 m forward, tilted; expressed for the optical frame.
  const gasp::Isometry3 T_robot_mrptcam =
      gasp::fromCPose3D(mrpt::poses::CPose3D(0.1, 0.02, 0.3, 5 * kDeg, 10 * kDeg, -3 * kDeg));
  f.T_robot_camera = T_robot_mrptcam * gasp::mrptCameraFromOptical();
  auto obs = gasp::observationFromFrame(f);
  // sensorPose comes back as the MRPT-frame pose.
  EXPECT_TRUE(gasp::fromCPose3D(obs->sensorPose).isApprox(T_robot_mrptcam, 1e-9));

  const gasp::OrganizedPointCloud cloud = gasp::backProject(f.depth_m, f.depth_intrinsics);
  ASSERT_EQ(cloud.countValid(), static_cast<std::size_t>(f.depth_m.total()));

  for (const bool with_sensor_pose : {false, true}) {
    mrpt::opengl::CPointCloud pts;
    mrpt::obs::T3DPointsProjectionParams pp;
    pp.takeIntoAccountSensorPoseOnRobot = with_sensor_pose;
    pp.USE_SSE2 = false;
    obs->unprojectInto(pts, pp);
    ASSERT_EQ(pts.size(), f.depth_m.total());
    const gasp::Isometry3 T_out_optical =
        with_sensor_pose ? f.T_robot_camera : gasp::mrptCameraFromOptical();
    double max_err = 0.0;
    for (int v = 0; v < f.depth_m.rows; ++v)
      for (int u = 0; u < f.depth_m.cols; ++u) {
        const auto& p = pts.getArrayPoints()[static_cast<std::size_t>(v * f.depth_m.cols + u)];
        const Eigen::Vector3d expected = T_out_optical * cloud.at(u, v).cast<double>();
        max_err = std::max(max_err, (Eigen::Vector3d(p.x, p.y, p.z) - expected).norm());
      }
    EXPECT_LT(max_err, 1e-4) << "sensor pose " << with_sensor_pose;  // float precision
  }
}

TEST(ObservationConversion, RoundTripKeepsEverything) {
  gasp::RgbdFrame f = gasp::test::syntheticFrame(1305031453.374112);
  f.depth_intrinsics.distortion = {0.2624, -0.9531, -0.0054, 0.0026, 1.1633};
  f.T_depth_rgb.translation() = Eigen::Vector3d(0.025, 0.001, -0.002);
  f.sensor_label = "KINECT";
  auto obs = gasp::observationFromFrame(f);
  EXPECT_FLOAT_EQ(obs->rangeUnits, 1.0f / 5000.0f);
  EXPECT_TRUE(obs->range_is_depth);
  EXPECT_TRUE(obs->hasIntensityImage);
  EXPECT_EQ(obs->intensityImageChannel, mrpt::obs::CObservation3DRangeScan::CH_VISIBLE);
  EXPECT_EQ(obs->cameraParams.distortion, mrpt::img::DistortionModel::plumb_bob);
  EXPECT_DOUBLE_EQ(obs->cameraParams.k3(), 1.1633);
  EXPECT_EQ(obs->cameraParamsIntensity.distortion, mrpt::img::DistortionModel::none);
  EXPECT_GE(obs->maxRange, 10.0f);
  EXPECT_EQ(obs->sensorLabel, "KINECT");
  EXPECT_EQ(obs->rangeImage(3, 5), f.depth_raw.at<std::uint16_t>(3, 5));
  // MRPT: the intensity camera 25 mm along the optical x (right) = 25 mm along MRPT's -Y.
  EXPECT_NEAR(obs->relativePoseIntensityWRTDepth.y(), -0.025, 1e-12);

  const gasp::RgbdFrame g = gasp::frameFromObservation(*obs);
  EXPECT_TRUE(gasp::test::sameMat(g.depth_raw, f.depth_raw));
  EXPECT_TRUE(gasp::test::sameMat(g.depth_m, f.depth_m));
  EXPECT_TRUE(gasp::test::sameMat(g.rgb, f.rgb));
  EXPECT_DOUBLE_EQ(g.depth_units_per_metre, 5000.0);
  EXPECT_EQ(g.depth_intrinsics, f.depth_intrinsics);
  EXPECT_EQ(g.rgb_intrinsics, f.rgb_intrinsics);
  EXPECT_NEAR(g.timestamp, f.timestamp, 1e-6);
  EXPECT_TRUE(g.T_depth_rgb.isApprox(f.T_depth_rgb, 1e-12));
  EXPECT_TRUE(g.T_robot_camera.isApprox(f.T_robot_camera, 1e-12));
  EXPECT_EQ(g.sensor_label, "KINECT");
}

TEST(ObservationConversion, RangesAlongRaysBecomeDepth) {
  const gasp::RgbdFrame f = gasp::test::syntheticFrame(2.0);
  auto obs = gasp::observationFromFrame(f);
  // Re-encode as true ranges (SwissRanger style) in millimetres.
  obs->range_is_depth = false;
  obs->rangeUnits = 0.001f;
  const auto& K = f.depth_intrinsics;
  cv::Mat expected(f.depth_m.size(), CV_32FC1);
  for (int v = 0; v < f.depth_m.rows; ++v)
    for (int u = 0; u < f.depth_m.cols; ++u) {
      const double d = f.depth_m.at<float>(v, u);
      const double range = d * Eigen::Vector3d((u - K.cx) / K.fx, (v - K.cy) / K.fy, 1.0).norm();
      const auto mm = static_cast<std::uint16_t>(std::lround(range * 1000.0));
      obs->rangeImage(v, u) = mm;
      expected.at<float>(v, u) = static_cast<float>(mm * 0.001 * d / range);
    }
  const gasp::RgbdFrame g = gasp::frameFromObservation(*obs);
  EXPECT_TRUE(g.depth_raw.empty());
  EXPECT_FALSE(g.hasRawDepth());
  EXPECT_LT(cv::norm(g.depth_m, expected, cv::NORM_INF), 1e-5);
  EXPECT_LT(cv::norm(g.depth_m, f.depth_m, cv::NORM_INF), 1e-3);  // mm quantisation
}

TEST(ObservationConversion, RangesAlongDistortedRaysBecomeDepth) {
  // A camera with fr1's lens: the range of pixel (u, v) runs along its undistorted ray. A plane
  // at depth 2 m gives ranges 2 |ray|; the conversion must give 2 m back at every pixel (pinhole
  // rays would be wrong by centimetres at the corners).
  gasp::RgbdFrame f = gasp::test::syntheticFrame(2.0, 640, 480);
  f.depth_intrinsics = gasp::CameraIntrinsics::tumFreiburg1();
  f.depth_m.setTo(2.0f);
  f.depth_raw = cv::Mat();
  f.rgb = cv::Mat();
  auto obs = gasp::observationFromFrame(f);
  obs->range_is_depth = false;
  obs->rangeUnits = 0.0001f;  // 0.1 mm
  const auto& K = f.depth_intrinsics;
  std::vector<cv::Point2f> pixels, rays;
  for (int v = 0; v < K.height; ++v)
    for (int u = 0; u < K.width; ++u) pixels.emplace_back(static_cast<float>(u), static_cast<float>(v));
  cv::undistortPoints(pixels, rays, cv::Matx33d(K.fx, 0, K.cx, 0, K.fy, K.cy, 0, 0, 1),
                      cv::Mat(1, 5, CV_64F, const_cast<double*>(K.distortion.data())));
  double worst_pinhole = 0.0;
  for (int v = 0; v < K.height; ++v)
    for (int u = 0; u < K.width; ++u) {
      const cv::Point2f& r = rays[static_cast<std::size_t>(v) * K.width + u];
      const double range = 2.0 * std::sqrt(1.0 + r.x * r.x + r.y * r.y);
      obs->rangeImage(v, u) = static_cast<std::uint16_t>(std::lround(range * 10000.0));
      const double kx = (u - K.cx) / K.fx, ky = (v - K.cy) / K.fy;
      worst_pinhole = std::max(worst_pinhole, std::abs(range / std::sqrt(1.0 + kx * kx + ky * ky) - 2.0));
    }
  const gasp::RgbdFrame g = gasp::frameFromObservation(*obs);
  EXPECT_EQ(g.depth_intrinsics, K);  // the coefficients are carried
  EXPECT_LT(cv::norm(g.depth_m, f.depth_m, cv::NORM_INF), 1e-3);
  EXPECT_GT(worst_pinhole, 0.01);  // what pinhole rays would have given
}

TEST(ObservationConversion, BadInputsThrow) {
  mrpt::obs::CObservation3DRangeScan no_range;
  no_range.sensorLabel = "CAM";
  try {
    gasp::frameFromObservation(no_range, "test scan");
    FAIL() << "expected gasp::Error";
  } catch (const gasp::Error& e) {
    EXPECT_NE(std::string(e.what()).find("no range image"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("test scan"), std::string::npos) << e.what();
  }
  auto obs = gasp::observationFromFrame(gasp::test::syntheticFrame(0.0));
  obs->cameraParams.ncols = 640;
  EXPECT_THROW(gasp::frameFromObservation(*obs), gasp::Error);  // size disagrees with K

  // What would otherwise pass as a quiet NaN or a hang: a NaN or absurd sensorPose, a principal
  // point far off the image, an intensity image of another size than its camera.
  const auto message = [](const mrpt::obs::CObservation3DRangeScan& o) {
    try {
      gasp::frameFromObservation(o, "scan");
    } catch (const gasp::Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  {
    auto bad = gasp::observationFromFrame(gasp::test::syntheticFrame(0.0));
    bad->sensorPose.x(std::nan(""));
    EXPECT_NE(message(*bad).find("sensorPose is not finite"), std::string::npos) << message(*bad);
    bad->sensorPose.x(1e20);
    EXPECT_NE(message(*bad).find("sensorPose"), std::string::npos) << message(*bad);
  }
  {
    auto bad = gasp::observationFromFrame(gasp::test::syntheticFrame(0.0));
    bad->cameraParams.setIntrinsicParamsFromValues(bad->cameraParams.fx(), bad->cameraParams.fy(), 1e12,
                                                  bad->cameraParams.cy());
    EXPECT_NE(message(*bad).find("principal point"), std::string::npos) << message(*bad);
  }
  {
    auto bad = gasp::observationFromFrame(gasp::test::syntheticFrame(0.0));
    ASSERT_TRUE(bad->hasIntensityImage);
    bad->cameraParamsIntensity.ncols *= 2;
    EXPECT_NE(message(*bad).find("intensity image is"), std::string::npos) << message(*bad);
  }

  gasp::RgbdFrame f = gasp::test::syntheticFrame(0.0);
  f.depth_intrinsics.width = 65;
  EXPECT_THROW(gasp::observationFromFrame(f), gasp::Error);
  gasp::RgbdFrame empty;
  EXPECT_THROW(gasp::observationFromFrame(empty), gasp::Error);
}

TEST(ObservationConversion, DepthAloneNeedsNoColourImage) {
  // Range and intensity images stored in external files; the colour file then goes missing.
  const std::string dir = gasp::test::scratchDir();
  const gasp::RgbdFrame f = gasp::test::syntheticFrame(3.0);
  auto obs = gasp::observationFromFrame(f);
  obs->rangeImage_convertToExternalStorage(dir + "/range.bin", dir + "/");
  ASSERT_TRUE(obs->intensityImage.saveToFile(dir + "/rgb.png"));
  obs->intensityImage.setExternalStorage(dir + "/rgb.png");
  obs->unload();
  const gasp::RgbdFrame both = gasp::frameFromObservation(*obs, "scan");
  EXPECT_TRUE(gasp::test::sameMat(both.rgb, f.rgb));
  obs->unload();
  std::filesystem::remove(dir + "/rgb.png");
  try {
    gasp::frameFromObservation(*obs, "scan");
    ADD_FAILURE() << "expected gasp::Error";
  } catch (const gasp::Error& e) {
    EXPECT_NE(std::string(e.what()).find("cannot load the intensity image"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("rgb.png"), std::string::npos) << e.what();
  }
  obs->unload();
  const gasp::RgbdFrame depth = gasp::frameFromObservation(*obs, "scan", gasp::ColourImage::Skip);
  EXPECT_TRUE(depth.rgb.empty());
  EXPECT_TRUE(gasp::test::sameMat(depth.depth_raw, f.depth_raw));
  EXPECT_EQ(depth.rgb_intrinsics.width, f.rgb_intrinsics.width);
  EXPECT_TRUE(depth.T_robot_camera.isApprox(f.T_robot_camera, 1e-12));
}

TEST(ObservationConversion, DepthWithoutRawIsQuantisedAtTumUnits) {
  gasp::RgbdFrame f = gasp::test::syntheticFrame(0.0);
  f.depth_raw.release();
  f.depth_units_per_metre = 0.0;
  f.rgb.release();
  auto obs = gasp::observationFromFrame(f);
  EXPECT_FALSE(obs->hasIntensityImage);
  const gasp::RgbdFrame g = gasp::frameFromObservation(*obs);
  EXPECT_LT(cv::norm(g.depth_m, f.depth_m, cv::NORM_INF), 1e-6);
  EXPECT_TRUE(g.rgb.empty());
}

// gasp::backProject() applies the pinhole model only (images are resampled before: makeDepthView,
// undistortion.h). MRPT 2.5's unprojectInto() builds
// its look-up table from cameraParams including the distortion model, so with TUM fr1/fr2
// intrinsics (plumb_bob) MRPT's point clouds are undistorted and differ from GASP's at the borders.
TEST(FrameConvention, MrptUnprojectionWithDistortionDiffersFromGasp) {
  gasp::RgbdFrame f = gasp::test::syntheticFrame(1.0, 640, 480);
  f.depth_intrinsics = gasp::CameraIntrinsics::tumFreiburg1();
  f.rgb.release();
  auto obs = gasp::observationFromFrame(f);
  ASSERT_EQ(obs->cameraParams.distortion, mrpt::img::DistortionModel::plumb_bob);
  mrpt::opengl::CPointCloud pts;
  mrpt::obs::T3DPointsProjectionParams pp;
  pp.USE_SSE2 = false;
  obs->unprojectInto(pts, pp);
  ASSERT_EQ(pts.size(), f.depth_m.total());
  const gasp::OrganizedPointCloud cloud = gasp::backProject(f.depth_m, f.depth_intrinsics);
  double centre_err = 0.0, max_err = 0.0;
  for (int v = 0; v < 480; ++v)
    for (int u = 0; u < 640; ++u) {
      const auto& p = pts.getArrayPoints()[static_cast<std::size_t>(v * 640 + u)];
      const Eigen::Vector3d expected = gasp::mrptCameraFromOptical() * cloud.at(u, v).cast<double>();
      const double err = (Eigen::Vector3d(p.x, p.y, p.z) - expected).norm();
      max_err = std::max(max_err, err);
      if (std::abs(u - 319) < 3 && std::abs(v - 255) < 3) centre_err = std::max(centre_err, err);
    }
  std::cout << "fr1 distortion: MRPT vs GASP unprojection, max " << max_err << " m, near the "
            << "principal point " << centre_err << " m\n";
  EXPECT_LT(centre_err, 1e-3);
  EXPECT_GT(max_err, 1e-3);
}
