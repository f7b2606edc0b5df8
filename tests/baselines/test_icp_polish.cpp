// polishPose (PCL GICP from a given pose): a perturbed pose returns to the truth on a synthetic
// room view; bad input gives a clear error or no estimate.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "gasp/baselines/icp_polish.h"
#include "gasp/core/error.h"
#include "gasp/core/pose.h"
#include "gasp/sim/simulation.h"

namespace gb = gasp::baselines;

namespace {

double angleDeg(const gasp::Isometry3& A, const gasp::Isometry3& B) {
  return gasp::rotationAngle(A.inverse() * B) * 180.0 / M_PI;
}
double distanceM(const gasp::Isometry3& A, const gasp::Isometry3& B) {
  return gasp::translationNorm(A.inverse() * B);
}

struct SimPair {
  cv::Mat source, target;
  gasp::CameraIntrinsics k = gasp::CameraIntrinsics::rosDefault();
  gasp::Isometry3 T_target_source;
};

/// Two views of the synthetic room, frames 3 and 6 (a few centimetres and degrees apart).
SimPair roomPair() {
  gasp::sim::SimulationOptions opt;
  opt.scene = "room";
  const gasp::sim::Simulation sim(opt);
  const auto a = sim.frame(3), b = sim.frame(6);
  SimPair p;
  p.source = a.depth;
  p.target = b.depth;
  p.T_target_source = b.T_world_camera.inverse() * a.T_world_camera;
  return p;
}

}  // namespace

TEST(IcpPolish, APerturbedPoseReturnsToTheTruth) {
  const SimPair p = roomPair();
  // 1.5 deg about a tilted axis and 3 cm: the size of the reference errors it is used to find.
  gasp::Isometry3 offset = gasp::Isometry3::Identity();
  offset.linear() = Eigen::AngleAxisd(1.5 * M_PI / 180.0, Eigen::Vector3d(0.3, 1.0, 0.2).normalized()).toRotationMatrix();
  offset.translation() = Eigen::Vector3d(0.02, -0.01, 0.02);
  const gasp::Isometry3 start = offset * p.T_target_source;
  ASSERT_GT(angleDeg(start, p.T_target_source), 1.4);
  const auto r = gb::polishPose(p.source, p.target, p.k, start);
  ASSERT_TRUE(r.success) << r.reason;
  EXPECT_GT(r.source_points, 1000u);
  EXPECT_LT(angleDeg(r.T_target_source, p.T_target_source), 0.25);
  EXPECT_LT(distanceM(r.T_target_source, p.T_target_source), 0.01);
  // From the truth it stays near the truth.
  const auto s = gb::polishPose(p.source, p.target, p.k, p.T_target_source);
  ASSERT_TRUE(s.success) << s.reason;
  EXPECT_LT(angleDeg(s.T_target_source, p.T_target_source), 0.25);
  EXPECT_LT(distanceM(s.T_target_source, p.T_target_source), 0.01);
}

TEST(IcpPolish, BadInput) {
  const SimPair p = roomPair();
  const gasp::Isometry3 I = gasp::Isometry3::Identity();
  // Empty and all-invalid depth: no estimate, with the reason.
  const cv::Mat zeros(p.k.height, p.k.width, CV_32FC1, cv::Scalar(0));
  const cv::Mat nans(p.k.height, p.k.width, CV_32FC1, cv::Scalar(std::numeric_limits<float>::quiet_NaN()));
  for (const cv::Mat* bad : {&zeros, &nans}) {
    const auto r = gb::polishPose(p.source, *bad, p.k, I);
    EXPECT_FALSE(r.success);
    EXPECT_NE(r.reason.find("too few points"), std::string::npos) << r.reason;
    EXPECT_TRUE(r.T_target_source.isApprox(I));
  }
  // Wrong type or size, a non-finite start, invalid parameters: errors.
  cv::Mat u16;
  p.source.convertTo(u16, CV_16UC1, 5000.0);
  EXPECT_THROW(gb::polishPose(u16, p.target, p.k, I), gasp::Error);
  EXPECT_THROW(gb::polishPose(p.source, p.target(cv::Rect(0, 0, 320, 240)).clone(), p.k, I), gasp::Error);
  gasp::Isometry3 nan_pose = I;
  nan_pose.translation().x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(gb::polishPose(p.source, p.target, p.k, nan_pose), gasp::Error);
  gb::IcpPolishParams params;
  params.voxel_m = 0.0;
  EXPECT_THROW(gb::polishPose(p.source, p.target, p.k, I, params), gasp::Error);
  params = {};
  params.max_iterations = 0;
  EXPECT_THROW(gb::validate(params), gasp::Error);
}
