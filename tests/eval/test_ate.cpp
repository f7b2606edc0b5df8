#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "gasp/core/error.h"
#include "gasp/eval/ate.h"

namespace {

/// N poses on a horizontal circle of radius r, 30 Hz stamps from t0, looking around.
gasp::Trajectory circle(int n, double r, double t0 = 100.0) {
  gasp::Trajectory traj;
  for (int i = 0; i < n; ++i) {
    const double a = 2.0 * M_PI * i / n;
    gasp::StampedPose p;
    p.timestamp = t0 + i / 30.0;
    p.T_world_camera = Eigen::Translation3d(r * std::cos(a), r * std::sin(a), 1.2) *
                       Eigen::AngleAxisd(a, Eigen::Vector3d::UnitZ());
    traj.push_back(p);
  }
  return traj;
}

gasp::Trajectory transformed(const gasp::Trajectory& traj, const gasp::Isometry3& T) {
  gasp::Trajectory out = traj;
  for (auto& p : out) p.T_world_camera = T * p.T_world_camera;
  return out;
}

const gasp::Isometry3 kSomeMotion = Eigen::Translation3d(3.0, -1.0, 0.5) *
                                    Eigen::AngleAxisd(2.0, Eigen::Vector3d(1, -2, 0.5).normalized());

}  // namespace

TEST(Ate, RigidlyMovedCopyHasZeroError) {
  const auto gt = circle(40, 1.5);
  const auto r = gasp::eval::computeAte(gt, transformed(gt, kSomeMotion));
  EXPECT_EQ(r.translation.count, 40u);
  EXPECT_LT(r.translation.rmse, 1e-9);
  EXPECT_TRUE(r.T_gt_est.isApprox(kSomeMotion.inverse(), 1e-9));
}

TEST(Ate, RadialOffsetGivesKnownError) {
  // Every estimated position is 5 cm further from the circle's centre: no rigid motion removes
  // that, and by symmetry the best alignment is the identity, so every error is exactly 5 cm.
  const auto gt = circle(36, 1.0);
  const auto est = transformed(circle(36, 1.05), kSomeMotion);
  const auto r = gasp::eval::computeAte(gt, est);
  EXPECT_NEAR(r.translation.rmse, 0.05, 1e-9);
  EXPECT_NEAR(r.translation.mean, 0.05, 1e-9);
  EXPECT_NEAR(r.translation.max, 0.05, 1e-9);
  EXPECT_NEAR(r.translation.std, 0.0, 1e-9);
}

TEST(Ate, TimestampWindowAndOffset) {
  const auto gt = circle(20, 1.0, 100.0);
  const auto late = circle(20, 1.0, 110.0);  // 10 s late: no stamp within the 20 ms window
  EXPECT_THROW(gasp::eval::computeAte(gt, late), gasp::Error);
  gasp::eval::AteOptions opt;
  opt.offset = -10.0;
  const auto r = gasp::eval::computeAte(gt, late, opt);
  EXPECT_EQ(r.translation.count, 20u);
  EXPECT_LT(r.translation.rmse, 1e-9);
}

TEST(Ate, ScaleOptionMultipliesEstimate) {
  const auto gt = circle(24, 1.0);
  auto half = gt;
  for (auto& p : half) p.T_world_camera.translation() *= 0.5;
  gasp::eval::AteOptions opt;
  opt.scale = 2.0;
  EXPECT_LT(gasp::eval::computeAte(gt, half, opt).translation.rmse, 1e-9);
  EXPECT_GT(gasp::eval::computeAte(gt, half).translation.rmse, 0.1);
}

TEST(Ate, AScaleThatOverflowsIsAnErrorNotNaN) {
  // gasp-eval --scale 1e160 printed "rmse: nan" with exit 0: the squares of 1e160 m overflow.
  const auto gt = circle(24, 1.0);
  gasp::eval::AteOptions opt;
  opt.scale = 1e160;
  try {
    gasp::eval::computeAte(gt, gt, opt);
    FAIL() << "expected gasp::Error";
  } catch (const gasp::Error& e) {
    EXPECT_NE(std::string(e.what()).find("not finite"), std::string::npos) << e.what();
  }
  for (double bad : {0.0, -2.0, std::nan(""), HUGE_VAL}) {
    opt.scale = bad;
    EXPECT_THROW(gasp::eval::computeAte(gt, gt, opt), gasp::Error) << bad;
  }
}
