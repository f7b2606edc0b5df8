#include <gtest/gtest.h>

#include <cmath>

#include "gasp/core/error.h"
#include "gasp/eval/pair_protocol.h"

using namespace gasp;
using namespace gasp::eval;

TEST(PairProtocol, PairsFromRegularlySpacedStarts) {
  const auto p = makePairs(10, 3, 2);
  ASSERT_EQ(p.size(), 4u);  // starts 0, 2, 4, 6 (8 + 3 > 9)
  EXPECT_EQ(p[0], std::make_pair(std::size_t{0}, std::size_t{3}));
  EXPECT_EQ(p[3], std::make_pair(std::size_t{6}, std::size_t{9}));
  EXPECT_TRUE(makePairs(3, 3, 1).empty());
  EXPECT_THROW(makePairs(10, 0, 1), Error);
  EXPECT_THROW(makePairs(10, 1, 0), Error);
}

TEST(PairProtocol, ScoreIsTheErrorOfTheRelativePose) {
  Isometry3 T_gt = Isometry3::Identity();
  T_gt.linear() = Eigen::AngleAxisd(1.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T_gt.translation() = Eigen::Vector3d(1, 2, 3);
  Isometry3 delta = Isometry3::Identity();
  delta.linear() = Eigen::AngleAxisd(2.0 * M_PI / 180.0, Eigen::Vector3d::UnitX()).toRotationMatrix();
  delta.translation() = Eigen::Vector3d(0.03, 0, 0.04);
  PairOutcome o;
  scorePose(T_gt * delta, T_gt, o);
  EXPECT_NEAR(o.t_err_m, 0.05, 1e-12);
  EXPECT_NEAR(o.r_err_deg, 2.0, 1e-9);
  scorePose(T_gt, T_gt, o);
  EXPECT_NEAR(o.t_err_m, 0.0, 1e-12);
  EXPECT_NEAR(o.r_err_deg, 0.0, 1e-6);
}

TEST(PairProtocol, SummaryCountsFailuresAndWrongEstimatesInFull) {
  std::vector<PairOutcome> o(4);
  for (auto& x : o) x.skip = 10;
  o[0] = {10, 0, 10, true, 0.03, 1.0, 50, ""};
  o[1] = {10, 5, 15, true, 0.04, 3.0, 70, ""};  // outside 2 deg
  o[2] = {10, 10, 20, false, 0, 0, 30, "no consensus"};
  o[3] = {20, 0, 20, true, 9.0, 90.0, 10, ""};  // another skip: ignored
  const auto s = summarise(o, 10, "gasp");
  EXPECT_EQ(s.pairs, 3u);
  EXPECT_EQ(s.failed, 1u);
  EXPECT_NEAR(s.rmse_t_m, std::sqrt((0.03 * 0.03 + 0.04 * 0.04) / 2), 1e-12);
  EXPECT_NEAR(s.rmse_r_deg, std::sqrt((1.0 + 9.0) / 2), 1e-12);
  EXPECT_NEAR(s.fail_pct, 100.0 / 3.0, 1e-9);
  EXPECT_NEAR(s.within_pct, 100.0 / 3.0, 1e-9);
  EXPECT_DOUBLE_EQ(s.median_ms, 50.0);
  EXPECT_EQ(csvHeader(), "skip,method,pairs,failed,rmse_t_m,rmse_r_deg,fail_pct,within_5cm_2deg_pct,median_ms");
  EXPECT_EQ(csvRow(s), "10,gasp,3,1,0.0354,2.236,33.3,33.3,50.0");
  const auto empty = summarise({}, 10, "gasp");
  EXPECT_EQ(empty.pairs, 0u);
  EXPECT_TRUE(std::isnan(empty.rmse_t_m));
  // Every pair failed: no RMSE (not 0, which would read as perfect), empty cells in the CSV.
  const auto failed = summarise({o[2]}, 10, "gasp");
  EXPECT_TRUE(std::isnan(failed.rmse_t_m) && std::isnan(failed.rmse_r_deg));
  EXPECT_EQ(csvRow(failed), "10,gasp,1,1,,,100.0,0.0,30.0");
}
