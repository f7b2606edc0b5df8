// A rolling-shutter pair deskewed with the velocity GASP measures between each frame's
// neighbours (rolling_shutter_deskew.h), end to end on the simulator's room.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <cstdio>
#include <utility>

#include "gasp/core/error.h"
#include "gasp/pipeline/rolling_shutter_deskew.h"
#include "synthetic_pairs.h"

namespace {

using gasp::CameraTwist;
using gasp::Isometry3;

constexpr double kReadout = 0.03;      // [s], first row to last
constexpr double kFrameStep = 1.0 / 30.0;

/// The pose at time t [s] of a camera through T_world_centre at t = 0 with a constant twist.
Isometry3 poseAt(const Isometry3& T_world_centre, const CameraTwist& twist, double t) {
  Isometry3 T_centre_t = Isometry3::Identity();
  const double w = twist.w_radps.norm();
  if (w > 0) T_centre_t.linear() = Eigen::AngleAxisd(w * t, twist.w_radps / w).toRotationMatrix();
  T_centre_t.translation() = twist.v_mps * t;
  return T_world_centre * T_centre_t;
}

/// The rolling-shutter depth image stamped at time t of that camera (rows exposed around t).
cv::Mat rollingFrame(const Isometry3& T_world_centre, const CameraTwist& twist, double t) {
  const auto& sim = gasp::test::simulation("room");
  const auto K = gasp::sim::SimulationOptions{}.intrinsics;
  return gasp::sim::renderRollingShutterFrame(
             sim.scene(), K,
             [&](int row) {
               return poseAt(T_world_centre, twist, t + (static_cast<double>(row) / (K.height - 1) - 0.5) * kReadout);
             })
      .depth;
}

struct MovingFrame {
  cv::Mat depth;                  ///< stamped at t = 0
  gasp::DepthView before, after;  ///< the neighbours at -1/30 s and +1/30 s
};

MovingFrame movingFrame(const Isometry3& T_world_centre, const CameraTwist& twist) {
  const auto K = gasp::sim::SimulationOptions{}.intrinsics;
  return {rollingFrame(T_world_centre, twist, 0.0),
          gasp::makeDepthView(rollingFrame(T_world_centre, twist, -kFrameStep), K),
          gasp::makeDepthView(rollingFrame(T_world_centre, twist, kFrameStep), K)};
}

CameraTwist makeTwist(Eigen::Vector3d v, Eigen::Vector3d w) {
  CameraTwist t;
  t.v_mps = v;
  t.w_radps = w;
  return t;
}

struct Errors {
  double t_m, r_deg;
};
Errors errors(const Isometry3& T_b_a, const gasp::PairResult& r) {
  const Isometry3 E = T_b_a.inverse() * r.pose.T_target_source;
  return {gasp::translationNorm(E), gasp::rotationAngle(E) * 180.0 / M_PI};
}

}  // namespace

TEST(RollingShutterDeskew, NeighbourVelocityUndoesTheSkewOfAPair) {
  const auto& sim = gasp::test::simulation("room");
  const auto K = gasp::sim::SimulationOptions{}.intrinsics;
  const Isometry3 C_a = sim.path().poses[3].T_world_camera, C_b = sim.path().poses[9].T_world_camera;
  // Opposite motions at the two frames, as a hand-held camera swinging back and forth: the
  // skews do not cancel in the relative pose.
  const CameraTwist twist_a = makeTwist({0.6, 0.1, 0.3}, {0.1, 0.4, 0.2});
  const CameraTwist twist_b = makeTwist({-0.6, 0.2, -0.3}, {0.3, -0.4, 0.0});
  const MovingFrame a = movingFrame(C_a, twist_a), b = movingFrame(C_b, twist_b);
  const Isometry3 T_b_a = gasp::relativePose(C_b, C_a);

  const auto skewed = gasp::registerViews(gasp::makeDepthView(a.depth, K), gasp::makeDepthView(b.depth, K));
  ASSERT_TRUE(skewed.pose.success) << skewed.pose.reason;
  const Errors e_skewed = errors(T_b_a, skewed);

  gasp::DeskewParams params;
  params.readout_s = kReadout;
  const auto da = gasp::deskewWithNeighbours(a.depth, K, a.before, a.after, 2 * kFrameStep, params);
  const auto db = gasp::deskewWithNeighbours(b.depth, K, b.before, b.after, 2 * kFrameStep, params);
  ASSERT_TRUE(da.deskewed) << da.reason;
  ASSERT_TRUE(db.deskewed) << db.reason;
  // The velocity measured between the neighbours (in the earlier neighbour's frame, 1/30 s of
  // rotation away from the stamp's) is the true one to a few per cent.
  for (const auto& [measured, truth] : {std::pair{da.twist, twist_a}, std::pair{db.twist, twist_b}}) {
    EXPECT_LT((measured.v_mps - truth.v_mps).norm(), 0.05 * truth.v_mps.norm()) << measured.v_mps.transpose();
    EXPECT_LT((measured.w_radps - truth.w_radps).norm(), 0.05 * truth.w_radps.norm()) << measured.w_radps.transpose();
  }

  const auto deskewed = gasp::registerViews(gasp::makeDepthView(da.depth_m, da.intrinsics),
                                            gasp::makeDepthView(db.depth_m, db.intrinsics));
  ASSERT_TRUE(deskewed.pose.success) << deskewed.pose.reason;
  const Errors e = errors(T_b_a, deskewed);
  std::printf("skewed %.4f m %.3f deg, deskewed %.4f m %.3f deg\n", e_skewed.t_m, e_skewed.r_deg, e.t_m, e.r_deg);
  EXPECT_GT(e_skewed.r_deg, 0.3) << "the skew must matter for this test to mean anything";
  EXPECT_LT(e.r_deg, e_skewed.r_deg / 3) << "skewed: " << e_skewed.t_m << " m " << e_skewed.r_deg << " deg";
  EXPECT_LT(e.t_m, e_skewed.t_m);
  EXPECT_LT(e.r_deg, 0.15);
  EXPECT_LT(e.t_m, 0.005);
}

TEST(RollingShutterDeskew, NoTrustedVelocityLeavesTheFrame) {
  const auto& sim = gasp::test::simulation("room");
  const auto K = gasp::sim::SimulationOptions{}.intrinsics;
  const MovingFrame a = movingFrame(sim.path().poses[3].T_world_camera, makeTwist({0.6, 0.1, 0.3}, {0.1, 0.4, 0.2}));
  gasp::DeskewParams params;
  params.readout_s = kReadout;

  params.max_speed_mps = 0.1;  // slower than the camera moves
  auto out = gasp::deskewWithNeighbours(a.depth, K, a.before, a.after, 2 * kFrameStep, params);
  EXPECT_FALSE(out.deskewed);
  EXPECT_NE(out.reason.find("implausible velocity"), std::string::npos) << out.reason;
  EXPECT_EQ(cv::norm(out.depth_m, a.depth, cv::NORM_INF), 0.0);

  params.max_speed_mps = 3.0;
  const gasp::DepthView empty = gasp::makeDepthView(cv::Mat::zeros(K.height, K.width, CV_32FC1), K);
  out = gasp::deskewWithNeighbours(a.depth, K, a.before, empty, 2 * kFrameStep, params);
  EXPECT_FALSE(out.deskewed);
  EXPECT_NE(out.reason.find("no pose between the neighbours"), std::string::npos) << out.reason;
  EXPECT_EQ(cv::norm(out.depth_m, a.depth, cv::NORM_INF), 0.0);

  params.readout_s = 0.0;
  out = gasp::deskewWithNeighbours(a.depth, K, a.before, a.after, 2 * kFrameStep, params);
  EXPECT_FALSE(out.deskewed);
  EXPECT_EQ(out.reason, "no readout time");
}

TEST(RollingShutterDeskew, BadParametersThrow) {
  const auto K = gasp::sim::SimulationOptions{}.intrinsics;
  const cv::Mat depth = cv::Mat::zeros(K.height, K.width, CV_32FC1);
  const gasp::DepthView view = gasp::makeDepthView(depth, K);
  gasp::DeskewParams params;
  params.readout_s = 0.03;
  EXPECT_THROW(gasp::deskewWithNeighbours(depth, K, view, view, 0.0, params), gasp::Error);
  params.readout_s = std::nan("");
  EXPECT_THROW(gasp::deskewWithNeighbours(depth, K, view, view, 0.066, params), gasp::Error);
  params.readout_s = 1e9;  // a frame is read out within its frame period, not in years
  EXPECT_THROW(gasp::validate(params), gasp::Error);
  params.readout_s = -0.03;  // bottom-up readouts are allowed
  EXPECT_NO_THROW(gasp::validate(params));
  params.readout_s = 0.03;
  params.max_rate_radps = 0.0;
  EXPECT_THROW(gasp::validate(params), gasp::Error);
}

TEST(RollingShutterDeskew, NeighbourFramesAtTheEndsOfASequence) {
  EXPECT_EQ(gasp::neighbourFrames(4, 9), (std::pair<std::size_t, std::size_t>{3, 5}));
  EXPECT_EQ(gasp::neighbourFrames(0, 9), (std::pair<std::size_t, std::size_t>{0, 1}));
  EXPECT_EQ(gasp::neighbourFrames(8, 9), (std::pair<std::size_t, std::size_t>{7, 8}));
  EXPECT_EQ(gasp::neighbourFrames(0, 1), (std::pair<std::size_t, std::size_t>{0, 0}));
}
