#include <gtest/gtest.h>

#include <fstream>

#include "gasp/core/error.h"
#include "gasp/core/tum_trajectory.h"
#include "gasp_test_data.h"

TEST(TumTrajectory, WriteReadRoundTrip) {
  gasp::Trajectory traj;
  for (int i = 0; i < 5; ++i) {
    gasp::StampedPose p;
    p.timestamp = 1305031102.160407 + 0.0333 * i;
    p.T_world_camera = Eigen::Translation3d(0.1 * i, -0.2, 1.0 + i) *
                       Eigen::AngleAxisd(0.3 * i, Eigen::Vector3d(1, 2, 3).normalized());
    traj.push_back(p);
  }
  const std::string path = gasp::test::scratchDir() + "/traj.txt";
  gasp::writeTumTrajectory(path, traj, "test");
  const auto back = gasp::readTumTrajectory(path);
  ASSERT_EQ(back.size(), traj.size());
  for (std::size_t i = 0; i < traj.size(); ++i) {
    EXPECT_NEAR(back[i].timestamp, traj[i].timestamp, 1e-6);
    EXPECT_TRUE(back[i].T_world_camera.isApprox(traj[i].T_world_camera, 1e-8));
  }
}

TEST(TumTrajectory, MalformedLinesNameFileAndLine) {
  const std::string path = gasp::test::scratchDir() + "/bad.txt";
  std::ofstream(path) << "# header\n1.0 0 0 0 0 0 0 1\n2.0 0 0 0 0 0 1\n";
  try {
    gasp::readTumTrajectory(path);
    FAIL();
  } catch (const gasp::Error& e) {
    EXPECT_NE(std::string(e.what()).find(path + ":3"), std::string::npos) << e.what();
  }
  std::ofstream(path) << "1.0 0 0 0 0 0 0 0\n";
  EXPECT_THROW(gasp::readTumTrajectory(path), gasp::Error);  // zero quaternion
  std::ofstream(path) << "1.0 0 0 nan 0 0 0 1\n";
  EXPECT_THROW(gasp::readTumTrajectory(path), gasp::Error);
  std::ofstream(path) << "1.0 0 0 0 0 0 0 1\n1.0 0 0 0 0 0 0 1\n";
  EXPECT_THROW(gasp::readTumTrajectory(path), gasp::Error);  // duplicate timestamp
  EXPECT_THROW(gasp::readTumTrajectory(path + ".missing"), gasp::Error);
}

TEST(TumTrajectory, FindNearestRespectsTolerance) {
  gasp::Trajectory traj(3);
  traj[0].timestamp = 1.00;
  traj[1].timestamp = 1.01;
  traj[2].timestamp = 1.05;
  EXPECT_EQ(gasp::findNearest(traj, 1.004, 0.02).value(), 0u);
  EXPECT_EQ(gasp::findNearest(traj, 1.007, 0.02).value(), 1u);
  EXPECT_EQ(gasp::findNearest(traj, 1.04, 0.02).value(), 2u);
  EXPECT_FALSE(gasp::findNearest(traj, 1.08, 0.02).has_value());
  EXPECT_FALSE(gasp::findNearest(traj, 0.9, 0.02).has_value());
  EXPECT_FALSE(gasp::findNearest(gasp::Trajectory{}, 1.0, 0.02).has_value());
}

TEST(TumTrajectory, AssociationIsGreedyOneToOneLikeAssociatePy) {
  // b[1] is closest to both a[0] and a[1]; associate.py gives it to the closer a[1], and a[0]
  // then takes b[0].
  const std::vector<double> a = {1.000, 1.012, 2.0};
  const std::vector<double> b = {0.995, 1.010, 1.5};
  const auto m = gasp::associateTimestamps(a, b, 0.02);
  ASSERT_EQ(m.size(), 2u);
  EXPECT_EQ(m[0], std::make_pair(std::size_t{0}, std::size_t{0}));
  EXPECT_EQ(m[1], std::make_pair(std::size_t{1}, std::size_t{1}));
  // With an offset, b is shifted before comparing.
  const auto shifted = gasp::associateTimestamps({2.0}, {1.5}, 0.02, 0.5);
  ASSERT_EQ(shifted.size(), 1u);
}
