// gasp::ObservationMatcher_GASP through the name-based factory, on real MRPT observations made
// from fr1_desk9 (skipped without the data) and on bad input.
#include <gtest/gtest.h>
#include <mrpt/obs/CObservation2DRangeScan.h>
#include <mrpt/obs/CObservation3DRangeScan.h>

#include <Eigen/LU>

#include <cmath>

#include "gasp/core/tum_dataset.h"
#include "gasp/mrpt/observation_matcher.h"
#include "gasp/rawlog/observation_conversion.h"
#include "gasp/rawlog/range_scan.h"
#include "gasp/rawlog/tum_to_rawlog.h"
#include "gasp/sim/lidar.h"
#include "gasp/sim/scene.h"
#include "gasp_test_data.h"

using namespace gasp;

namespace {

/// TUM frame i as an MRPT observation, the robot frame placed away from the camera so that the
/// sensorPose handling is exercised; optionally without the intensity image (range-only).
mrpt::obs::CObservation3DRangeScan::Ptr observation(const TumDataset& ds, std::size_t i, bool rgb,
                                                    const Isometry3& T_robot_camera) {
  RgbdFrame f = frameFromTum(ds, i, rgb);
  f.T_robot_camera = T_robot_camera;
  return observationFromFrame(f);
}

Isometry3 someMount() {
  Isometry3 S = Isometry3::Identity();
  S.linear() = Eigen::AngleAxisd(0.3, Eigen::Vector3d(0.2, 1.0, 0.1).normalized()).toRotationMatrix();
  S.translation() = Eigen::Vector3d(0.2, -0.1, 0.5);
  return S;
}

}  // namespace

TEST(ObservationMatcher, CreatedByNameRecoversTheRelativePose) {
  GASP_REQUIRE_DATA(dir, "tum/fr1_desk9");
  const auto ds = TumDataset::open(dir);
  ASSERT_TRUE(ds.frame(0).T_world_camera && ds.frame(4).T_world_camera);
  const Isometry3 S = someMount();
  for (const bool rgb : {true, false}) {
    const auto a = observation(ds, 0, rgb, S), b = observation(ds, 4, rgb, S);
    const auto matcher = createObservationMatcher("gasp::ObservationMatcher_GASP");
    const MatchConstraint c = matcher->match(*a, *b);
    ASSERT_TRUE(c.success) << c.reason;
    // Truth in robot frames: T_ra_rb = S T_ca_cb S^-1.
    const Isometry3 T_ca_cb = relativePose(*ds.frame(0).T_world_camera, *ds.frame(4).T_world_camera);
    const Isometry3 E = (S * T_ca_cb * S.inverse()).inverse() * fromCPose3D(c.T_a_b);
    EXPECT_LT(translationNorm(E), 0.03) << (rgb ? "rgb-d" : "range-only");
    EXPECT_LT(rotationAngle(E) * 180.0 / M_PI, 2.0) << (rgb ? "rgb-d" : "range-only");
    EXPECT_GT(c.inliers, 8);
    EXPECT_FALSE(c.associations.empty());
    EXPECT_TRUE(c.information.isApprox(c.information.transpose(), 1e-6 * c.information.norm()));
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> eig(c.information);
    EXPECT_GT(eig.eigenvalues().minCoeff(), 0.0);
    // The edge information (with the model error, 1 cm and 0.75 deg per axis in the camera frame),
    // not the refinement's sub-millimetre one: no axis is more certain than the model error.
    const Eigen::Matrix<double, 6, 6> C = c.information.inverse();
    for (int k = 0; k < 3; ++k) {
      EXPECT_GE(std::sqrt(C(k, k)), 0.0099) << "translation axis " << k;
      EXPECT_GE(std::sqrt(C(k + 3, k + 3)) * 180.0 / M_PI, 0.74) << "rotation axis " << k;
    }
  }
}

TEST(ObservationMatcher, ParametersFromYaml) {
  using mrpt::containers::yaml;
  EXPECT_NO_THROW(createObservationMatcher("gasp::ObservationMatcher_GASP",
                                           yaml::FromText("candidates: 20\nmutual_check: false\n")));
  EXPECT_NO_THROW(createObservationMatcher("gasp::ObservationMatcher_GASP",
                                           yaml::FromText("dense_max_rounds: 4\ndense_converged_m: 0.001\n")));
  EXPECT_THROW(createObservationMatcher("gasp::ObservationMatcher_GASP", yaml::FromText("dense_max_rounds: -2\n")),
               std::exception);
  EXPECT_NO_THROW(createObservationMatcher("gasp::ObservationMatcher_GASP",
                                           yaml::FromText("model_error_t_m: 0.01\nmodel_error_r_deg: 1.0\n")));
  EXPECT_THROW(createObservationMatcher("gasp::ObservationMatcher_GASP", yaml::FromText("model_error_t_m: -0.01\n")),
               std::exception);
  EXPECT_THROW(createObservationMatcher("gasp::ObservationMatcher_GASP", yaml::FromText("candidatez: 20\n")),
               std::exception);
  EXPECT_THROW(createObservationMatcher("gasp::ObservationMatcher_GASP", yaml::FromText("lambda: 3.0\n")),
               std::exception);
  EXPECT_THROW(createObservationMatcher("gasp::NoSuchMatcher"), std::exception);
  try {  // the interface itself is registered but abstract: said so, not "not registered"
    createObservationMatcher("gasp::ObservationMatcher");
    ADD_FAILURE() << "the abstract interface was created";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("abstract"), std::string::npos) << e.what();
  }
  EXPECT_THROW(createObservationMatcher("mrpt::obs::CObservation2DRangeScan"), std::exception);
}

TEST(ObservationMatcher, BadObservationsGiveClearErrors) {
  const auto matcher = createObservationMatcher("gasp::ObservationMatcher_GASP");
  mrpt::obs::CObservation2DRangeScan laser;
  mrpt::obs::CObservation3DRangeScan empty;  // no range image
  EXPECT_THROW(matcher->match(laser, laser), std::exception);
  EXPECT_THROW(matcher->match(empty, empty), std::exception);
  // All-zero depth: a valid observation with nothing in it -> no estimate with a reason.
  RgbdFrame f;
  f.depth_m = cv::Mat::zeros(480, 640, CV_32FC1);
  const auto zero = observationFromFrame(f);
  const MatchConstraint c = matcher->match(*zero, *zero);
  EXPECT_FALSE(c.success);
  EXPECT_FALSE(c.reason.empty());
}

TEST(ObservationMatcher, OnePlaneGivesAPartialPoseWithItsFreeDirections) {
  // Two views of one plane 1.5 m in front (the camera mounted on the robot): no full pose, a
  // partial one whose information is zero along each free direction, given in the robot frame.
  RgbdFrame f;
  f.depth_m = cv::Mat(480, 640, CV_32FC1, cv::Scalar(1.5f));
  f.T_robot_camera = someMount();
  const auto a = observationFromFrame(f), b = observationFromFrame(f);
  const auto matcher = createObservationMatcher("gasp::ObservationMatcher_GASP");
  const MatchConstraint c = matcher->match(*a, *b);
  EXPECT_FALSE(c.success);
  ASSERT_TRUE(c.partial) << c.reason;
  EXPECT_TRUE(c.degenerate);
  ASSERT_EQ(c.free_directions.cols(), 3);
  EXPECT_NE(c.reason.find("partial pose, free: "), std::string::npos) << c.reason;
  for (Eigen::Index k = 0; k < 3; ++k) {
    EXPECT_NEAR(c.free_directions.col(k).norm(), 1.0, 1e-9);
    EXPECT_LT((c.information * c.free_directions.col(k)).norm(), 1e-6 * c.information.norm());
  }
  // The plane's normal in the robot frame (the camera's optical axis, mounted) is observed: a
  // translation along it is no free direction.
  const Eigen::Vector3d normal = someMount().linear() * Eigen::Vector3d::UnitZ();
  Eigen::Matrix<double, 6, 1> along_normal;
  along_normal << normal, Eigen::Vector3d::Zero();
  EXPECT_GT(along_normal.dot(c.information * along_normal), 0.0);
}

// Two simulated sweeps given as point clouds (CObservationPointCloud): their layout is found from
// the points (rangeScanFrom()), and the matcher gives the robots' relative pose within 5 cm /
// 0.5 deg; 32 lasers, as the aligner's point-cloud test.
TEST(ObservationMatcher, TwoPointCloudSweepsGiveTheRobotsRelativePose) {
  const sim::Scene room = sim::makeScene("room");
  Isometry3 T_a = Isometry3::Identity(), T_b = Isometry3::Identity();
  T_a.translation() = Eigen::Vector3d(0.3, -0.2, 1.0);
  T_b.linear() = Eigen::AngleAxisd(0.6, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T_b.translation() = Eigen::Vector3d(1.1, 0.4, 1.05);
  Isometry3 S = Isometry3::Identity();  // the LiDAR 0.8 m up on the robot
  S.translation() = Eigen::Vector3d(0.1, 0.0, 0.8);
  const sim::LidarSensor lidar = sim::lidarSensor(32);
  auto a = toPointCloud(sim::simulateLidarScan(room, lidar, T_a, 1, 0), "CLOUD");
  auto b = toPointCloud(sim::simulateLidarScan(room, lidar, T_b, 1, 1), "CLOUD");
  a.setSensorPose(toCPose3D(S));
  b.setSensorPose(toCPose3D(S));
  const auto matcher = createObservationMatcher("gasp::ObservationMatcher_GASP");
  const MatchConstraint c = matcher->match(a, b);
  ASSERT_TRUE(c.success) << c.reason;
  const Isometry3 E = (S * (T_a.inverse() * T_b) * S.inverse()).inverse() * fromCPose3D(c.T_a_b);
  EXPECT_LT(translationNorm(E), 0.05);
  EXPECT_LT(rotationAngle(E) * 180.0 / M_PI, 0.5);
}

// Two simulated 16-laser sweeps as MRPT's CObservationRotatingScan (toRotatingScan), mounted on a
// robot: the matcher takes them with the LiDAR's values (the params file form's section lidar)
// and gives the robots' relative pose within the 5 cm / 0.5 deg; a sweep against a depth
// image is refused with both classes named.
TEST(ObservationMatcher, TwoLidarSweepsGiveTheRobotsRelativePose) {
  const sim::Scene room = sim::makeScene("room");
  Isometry3 T_a = Isometry3::Identity(), T_b = Isometry3::Identity();
  T_a.translation() = Eigen::Vector3d(0.3, -0.2, 1.0);
  T_b.linear() = Eigen::AngleAxisd(0.6, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T_b.translation() = Eigen::Vector3d(1.1, 0.4, 1.05);
  Isometry3 S = Isometry3::Identity();  // the LiDAR 0.8 m up on the robot, turned 90 deg
  S.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  S.translation() = Eigen::Vector3d(0.1, 0.0, 0.8);
  const sim::LidarSensor lidar = sim::lidarSensor(16);
  auto a = toRotatingScan(sim::simulateLidarScan(room, lidar, T_a, 1, 0), "LIDAR");
  auto b = toRotatingScan(sim::simulateLidarScan(room, lidar, T_b, 1, 1), "LIDAR");
  a.setSensorPose(toCPose3D(S));
  b.setSensorPose(toCPose3D(S));
  const auto matcher = createObservationMatcher("gasp::ObservationMatcher_GASP",
                                                mrpt::containers::yaml::FromText("lidar:\n  patch_area_m2: 0.5\n"));
  const MatchConstraint c = matcher->match(a, b);
  ASSERT_TRUE(c.success) << c.reason;
  const Isometry3 E = (S * (T_a.inverse() * T_b) * S.inverse()).inverse() * fromCPose3D(c.T_a_b);
  EXPECT_LT(translationNorm(E), 0.05);
  EXPECT_LT(rotationAngle(E) * 180.0 / M_PI, 0.5);
  EXPECT_GT(c.inliers, 5);
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> eig(c.information);
  EXPECT_GT(eig.eigenvalues().minCoeff(), 0.0);

  RgbdFrame f;
  f.depth_m = cv::Mat::zeros(480, 640, CV_32FC1);
  const auto depth = observationFromFrame(f);
  try {
    matcher->match(a, *depth);
    ADD_FAILURE() << "a sweep was matched against a depth image";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("CObservation3DRangeScan"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("one kind"), std::string::npos) << e.what();
  }
}
