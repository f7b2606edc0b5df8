#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "gasp/core/error.h"
#include "gasp/eval/rpe.h"

namespace {

/// n poses, 0.1 s apart; each step moves `step` along the camera's x and yaws by `yaw_deg`.
gasp::Trajectory walk(int n, double step, double yaw_deg) {
  gasp::Trajectory traj;
  gasp::Isometry3 T = gasp::Isometry3::Identity();
  for (int i = 0; i < n; ++i) {
    traj.push_back({10.0 + 0.1 * i, T});
    T = T * Eigen::Translation3d(step, 0, 0) *
        Eigen::AngleAxisd(yaw_deg * M_PI / 180.0, Eigen::Vector3d::UnitZ());
  }
  return traj;
}

}  // namespace

TEST(Rpe, IdenticalTrajectoriesHaveZeroError) {
  const auto gt = walk(30, 0.1, 5.0);
  gasp::eval::RpeOptions opt;
  opt.delta = 1;
  opt.unit = gasp::eval::DeltaUnit::Frames;
  const auto r = gasp::eval::computeRpe(gt, gt, opt);
  EXPECT_LT(r.translation.max, 1e-12);
  EXPECT_LT(r.rotation_deg.max, 1e-6);
}

TEST(Rpe, KnownTranslationDrift) {
  // 1 cm too long per step, no rotation: every 1-frame pair is off by 1 cm, every 3-frame pair
  // by 3 cm. As evaluate_rpe.py, pairs ending on the last pose are dropped: n - delta - 1 pairs.
  const auto gt = walk(20, 0.10, 0.0);
  const auto est = walk(20, 0.11, 0.0);
  gasp::eval::RpeOptions opt;
  opt.unit = gasp::eval::DeltaUnit::Frames;
  opt.delta = 1;
  auto r = gasp::eval::computeRpe(gt, est, opt);
  EXPECT_EQ(r.pairs.size(), 18u);
  EXPECT_NEAR(r.translation.rmse, 0.01, 1e-12);
  EXPECT_NEAR(r.rotation_deg.rmse, 0.0, 1e-9);
  opt.delta = 3;
  r = gasp::eval::computeRpe(gt, est, opt);
  EXPECT_EQ(r.pairs.size(), 16u);
  EXPECT_NEAR(r.translation.median, 0.03, 1e-12);
}

TEST(Rpe, KnownRotationDriftAndSecondsUnit) {
  const auto gt = walk(20, 0.0, 10.0);
  const auto est = walk(20, 0.0, 11.0);
  gasp::eval::RpeOptions opt;  // default unit: seconds; poses are 0.1 s apart
  opt.delta = 0.2;
  const auto r = gasp::eval::computeRpe(gt, est, opt);
  EXPECT_EQ(r.pairs.size(), 17u);
  for (const auto& p : r.pairs) EXPECT_EQ(p.est_j, p.est_i + 2);
  EXPECT_NEAR(r.rotation_deg.mean, 2.0, 1e-9);
  EXPECT_NEAR(r.translation.mean, 0.0, 1e-12);
}

TEST(Rpe, BadInputThrows) {
  const auto gt = walk(10, 0.1, 0.0);
  EXPECT_THROW(gasp::eval::computeRpe(gt, {}), gasp::Error);
  gasp::eval::RpeOptions opt;
  opt.delta = -1;
  EXPECT_THROW(gasp::eval::computeRpe(gt, gt, opt), gasp::Error);
  auto far = gt;
  for (auto& p : far) p.timestamp += 100.0;  // no overlap in time
  EXPECT_THROW(gasp::eval::computeRpe(gt, far), gasp::Error);
}

TEST(Rpe, ADeltaBelowThePoseSpacingPairsNoPoseWithItself) {
  // Poses are 0.1 s apart: a delta of 1e-300 s would find each pose itself, an error of 0 that
  // measures nothing. Such pairs are left out; with none left it is an error saying why.
  const auto gt = walk(10, 0.1, 0.0);
  gasp::eval::RpeOptions opt;
  opt.delta = 1e-300;
  try {
    gasp::eval::computeRpe(gt, gt, opt);
    FAIL() << "expected gasp::Error";
  } catch (const gasp::Error& e) {
    EXPECT_NE(std::string(e.what()).find("below the poses' spacing"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("1e-300"), std::string::npos) << e.what();
  }
  opt.delta = 0.04;  // closer to a pose itself than to the next one (0.1 s on)
  EXPECT_THROW(gasp::eval::computeRpe(gt, gt, opt), gasp::Error);
  opt.delta = 0.06;  // nearer the next pose: every pair spans one step
  const auto r = gasp::eval::computeRpe(gt, gt, opt);
  for (const auto& p : r.pairs) EXPECT_EQ(p.est_j, p.est_i + 1);
}

TEST(Rpe, ScaleAndDeltaMustBeFiniteAndErrorsFinite) {
  const auto gt = walk(30, 0.1, 0.0);  // 2.9 s: pairs at the default delta of 1 s
  gasp::eval::RpeOptions opt;
  for (double bad : {0.0, -1.0, std::nan(""), HUGE_VAL}) {
    opt = {};
    opt.scale = bad;
    EXPECT_THROW(gasp::eval::computeRpe(gt, gt, opt), gasp::Error) << bad;
    opt = {};
    opt.delta = bad;
    EXPECT_THROW(gasp::eval::computeRpe(gt, gt, opt), gasp::Error) << bad;
  }
  opt = {};
  opt.scale = 1e308;  // 0.1 m steps times 1e308 overflow to inf: an error, not "rmse: nan"
  try {
    gasp::eval::computeRpe(gt, gt, opt);
    FAIL() << "expected gasp::Error";
  } catch (const gasp::Error& e) {
    EXPECT_NE(std::string(e.what()).find("not finite"), std::string::npos) << e.what();
  }
}
