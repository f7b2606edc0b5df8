// scene_change.h: the scene-change attempt's parameters and the prediction gate.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "gasp/core/error.h"
#include "gasp/odometry/odometry_params.h"
#include "gasp/odometry/scene_change.h"

namespace {

using gasp::Isometry3;
using gasp::SceneChangeParams;

Isometry3 pose(double x, double yaw_deg) {
  Isometry3 T = Isometry3::Identity();
  T.linear() = Eigen::AngleAxisd(yaw_deg * M_PI / 180.0, Eigen::Vector3d::UnitY()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(x, 0.1, 0.2);
  return T;
}

std::string errorOf(const SceneChangeParams& p) {
  try {
    gasp::validate(p);
  } catch (const gasp::Error& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace

TEST(SceneChange, TheGateGrowsWithTheTimeSinceTheReference) {
  const SceneChangeParams p;  // 2 cm + 2 m/s^2 dt^2 / 2, 2 deg + 5 rad/s^2 dt^2 / 2
  const Isometry3 predicted = pose(0.5, 10.0);
  // At 30 Hz the floors dominate: 2.1 cm / 2.2 deg.
  auto g = gasp::predictionGate(pose(0.515, 11.5), predicted, 1.0 / 30, p);
  EXPECT_NEAR(g.gate_m, 0.02 + 1.0 / 900, 1e-12);
  EXPECT_NEAR(g.gate_deg, 2.0 + 2.5 / 900 * 180.0 / M_PI, 1e-9);
  EXPECT_NEAR(g.off_m, 0.015, 1e-12);
  EXPECT_NEAR(g.off_deg, 1.5, 1e-9);
  EXPECT_TRUE(g.within());
  EXPECT_FALSE(gasp::predictionGate(pose(0.53, 10.0), predicted, 1.0 / 30, p).within());  // 3 cm off
  EXPECT_FALSE(gasp::predictionGate(pose(0.5, 13.0), predicted, 1.0 / 30, p).within());   // 3 deg off
  // At 5 Hz: 6 cm / 7.73 deg.
  g = gasp::predictionGate(pose(0.55, 16.0), predicted, 0.2, p);
  EXPECT_NEAR(g.gate_m, 0.06, 1e-12);
  EXPECT_NEAR(g.gate_deg, 2.0 + 0.1 * 180.0 / M_PI, 1e-9);
  EXPECT_TRUE(g.within());
  EXPECT_FALSE(gasp::predictionGate(pose(0.57, 10.0), predicted, 0.2, p).within());
  EXPECT_FALSE(gasp::predictionGate(pose(0.5, 18.0), predicted, 0.2, p).within());
  // A quarter turn or a half turn is never within a gate of a frame's time.
  EXPECT_FALSE(gasp::predictionGate(pose(0.5, 100.0), predicted, 0.2, p).within());
  EXPECT_FALSE(gasp::predictionGate(pose(0.5, 190.0), predicted, 0.2, p).within());
}

TEST(SceneChange, ALongPredictionVouchesForNothing) {
  const SceneChangeParams p;  // at most 0.10 m / 10 deg: frames up to 0.236 s apart
  EXPECT_EQ(gasp::predictionTooWide(1.0 / 30, p), "");
  EXPECT_EQ(gasp::predictionTooWide(0.2, p), "");
  EXPECT_EQ(gasp::predictionTooWide(0.25, p),
            "not tried: over 0.250 s the prediction's gate, 0.083 m / 10.95 deg, is wider than 0.100 m / 10.00 deg");
  // fr3_cabinet_kf's keyframes four apart.
  EXPECT_NE(gasp::predictionTooWide(2.7, p).find("7.310 m"), std::string::npos) << gasp::predictionTooWide(2.7, p);
  SceneChangeParams wide = p;
  wide.max_gate_m = 10.0;
  wide.max_gate_deg = 1e6;
  EXPECT_EQ(gasp::predictionTooWide(2.7, wide), "");
}

TEST(SceneChange, TheReasonSaysHowFarAndTheGate) {
  const auto g = gasp::predictionGate(pose(0.6, 10.0), pose(0.5, 10.0), 0.2, SceneChangeParams{});
  EXPECT_EQ(g.describe(), "0.100 m / 0.00 deg from the constant-velocity prediction (gate 0.060 m / 7.73 deg)");
}

TEST(SceneChange, ANaNPoseIsNotWithinTheGate) {
  Isometry3 bad = pose(0.5, 10.0);
  bad.translation().x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(gasp::predictionGate(bad, pose(0.5, 10.0), 0.2, SceneChangeParams{}).within());
  Isometry3 bad_rotation = pose(0.5, 10.0);
  bad_rotation.linear()(0, 0) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(gasp::predictionGate(bad_rotation, pose(0.5, 10.0), 0.2, SceneChangeParams{}).within());
}

TEST(SceneChange, ThePairParametersLoosenOnlyTheVisibilityLimits) {
  gasp::PairParams pair;
  pair.associate.candidates = 7;
  SceneChangeParams p;
  p.max_violation_ratio = 0.4;
  p.max_two_way_violation_ratio = 0.2;
  p.max_occluded_ratio = 0.7;
  const gasp::PairParams loose = gasp::sceneChangePairParams(pair, p);
  EXPECT_EQ(loose.certify.visibility.max_violation_ratio, 0.4);
  EXPECT_EQ(loose.certify.visibility.max_two_way_violation_ratio, 0.2);
  EXPECT_EQ(loose.certify.visibility.max_occluded_ratio, 0.7);
  EXPECT_EQ(loose.certify.fallback_max_violation_ratio, 0.4);  // the fallback's and the retry's limit
  EXPECT_EQ(loose.associate.candidates, 7);
  EXPECT_EQ(loose.certify.visibility.gate_m, pair.certify.visibility.gate_m);
  EXPECT_EQ(loose.certify.visibility.min_consistent, pair.certify.visibility.min_consistent);
  EXPECT_EQ(loose.retry.finer_area_factor, pair.retry.finer_area_factor);
  EXPECT_NO_THROW(gasp::validate(loose));
}

TEST(SceneChange, InvalidParametersAreErrorsThatNameTheField) {
  const auto with = [](auto set) {
    SceneChangeParams p;
    set(p);
    return errorOf(p);
  };
  EXPECT_EQ(errorOf(SceneChangeParams{}), "(no error)");
  EXPECT_NE(with([](SceneChangeParams& p) { p.max_violation_ratio = 1.5; }).find("scene_change.max_violation_ratio"),
            std::string::npos);
  EXPECT_NE(with([](SceneChangeParams& p) { p.max_two_way_violation_ratio = -0.1; })
                .find("scene_change.max_two_way_violation_ratio"),
            std::string::npos);
  EXPECT_NE(with([](SceneChangeParams& p) { p.max_occluded_ratio = std::nan(""); }).find("scene_change.max_occluded_ratio"),
            std::string::npos);
  EXPECT_NE(with([](SceneChangeParams& p) { p.gate_m = 0; }).find("scene_change.gate_m"), std::string::npos);
  EXPECT_NE(with([](SceneChangeParams& p) { p.gate_deg = -1; }).find("scene_change.gate_deg"), std::string::npos);
  EXPECT_NE(with([](SceneChangeParams& p) { p.max_accel_mps2 = INFINITY; }).find("scene_change.max_accel_mps2"),
            std::string::npos);
  EXPECT_NE(with([](SceneChangeParams& p) { p.max_gate_m = 0; }).find("scene_change.max_gate_m"), std::string::npos);
  EXPECT_NE(with([](SceneChangeParams& p) { p.max_gate_deg = NAN; }).find("scene_change.max_gate_deg"), std::string::npos);
  EXPECT_NE(with([](SceneChangeParams& p) { p.max_angular_accel_radps2 = -1; })
                .find("scene_change.max_angular_accel_radps2"),
            std::string::npos);
  // The odometry's validate() checks them too.
  gasp::OdometryParams odometry;
  odometry.scene_change.gate_m = -1;
  EXPECT_THROW(gasp::validate(odometry), gasp::Error);
}
