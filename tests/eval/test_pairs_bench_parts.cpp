// gasp-pairs' pieces (rawlog_tools/gasp-pairs): the pairs CSV's lines, the reference each pair is
// scored against, and the printed table. The whole program is tested in
// tests/pipeline/test_programs.cpp and tests/baselines/test_pairs_program.cpp.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "gasp/core/camera_roll.h"
#include "gasp/core/tum_dataset.h"
#include "gasp_test_data.h"
#include "pair_reference.h"
#include "pairs_csv.h"
#include "pairs_table.h"

namespace {

using gasp::Isometry3;

/// RFC 4180 fields of one line.
std::vector<std::string> splitCsv(const std::string& line) {
  std::vector<std::string> out(1);
  bool quoted = false;
  for (std::size_t k = 0; k < line.size(); ++k) {
    const char c = line[k];
    if (quoted) {
      if (c == '"' && k + 1 < line.size() && line[k + 1] == '"') out.back() += '"', ++k;
      else if (c == '"') quoted = false;
      else out.back() += c;
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      out.emplace_back();
    } else {
      out.back() += c;
    }
  }
  return out;
}

std::map<std::string, std::string> fieldsByName(const std::string& row) {
  const auto names = splitCsv(gasp::pairs::pairsCsvHeader());
  const auto values = splitCsv(row);
  EXPECT_EQ(values.size(), names.size()) << row;
  std::map<std::string, std::string> m;
  for (std::size_t k = 0; k < names.size() && k < values.size(); ++k) m[names[k]] = values[k];
  return m;
}

Isometry3 pose(double angle_rad, const Eigen::Vector3d& axis, const Eigen::Vector3d& t) {
  Isometry3 T = Isometry3::Identity();
  T.linear() = Eigen::AngleAxisd(angle_rad, axis.normalized()).toRotationMatrix();
  T.translation() = t;
  return T;
}

double number(const std::string& s) { return std::stod(s); }

}  // namespace

TEST(PairsCsv, AFailedRunHasEveryFieldAndLeavesTheMissingOnesEmpty) {
  gasp::eval::PairOutcome o;
  o.skip = 10, o.from = 3, o.to = 13, o.ms = 12.5;
  o.reason = "too few associations, \"3\" of 12";  // a comma and quotes survive the CSV
  gasp::pairs::MethodRun run;
  run.reason = o.reason;
  gasp::pairs::PairsCsvChecks checks;
  checks.T_gt = pose(0.1, {0, 0, 1}, {0.3, 0.4, 0});
  auto f = fieldsByName(gasp::pairs::pairsCsvRow(o, "gasp", run, checks));
  EXPECT_EQ(f["skip"], "10");
  EXPECT_EQ(f["method"], "gasp");
  EXPECT_EQ(f["from"], "3");
  EXPECT_EQ(f["to"], "13");
  EXPECT_EQ(f["estimated"], "0");
  for (const char* empty : {"t_err_m", "r_err_deg", "precision", "verified", "verified_precision", "agreement", "tx",
                            "qw", "ref_icp_t_m", "est_vs_ref_icp_t_m", "est_icp_t_m", "rgb_inliers",
                            "rgb_r_vs_ref_deg", "nees", "nees_refinement"})
    EXPECT_EQ(f[empty], "") << empty;
  EXPECT_NEAR(number(f["motion_t_m"]), 0.5, 1e-6);  // the pair's true motion is there without an estimate
  EXPECT_NEAR(number(f["motion_r_deg"]), 0.1 * 180 / M_PI, 1e-4);
  EXPECT_EQ(f["reason"], o.reason);
}

TEST(PairsCsv, AnEstimateWithEveryCheckFillsItsColumns) {
  gasp::eval::PairOutcome o;
  o.skip = 1, o.from = 0, o.to = 1, o.estimated = true, o.t_err_m = 0.01, o.r_err_deg = 0.5;
  gasp::pairs::MethodRun run;
  run.estimated = true;
  run.T_target_source = pose(0.2, {0, 1, 0}, {0.1, -0.2, 0.3});
  run.associations = 120, run.inliers = 80;
  run.violation_ratio = 0.04, run.violation_ratio_lesser = 0.01;
  run.violation_blob_share_lesser = 0.25, run.violation_blob_share = 0.5;
  run.free_quality = gasp::AssociationQuality{100, 40, 200};
  run.verified_quality = gasp::AssociationQuality{150, 140, 200};
  run.nees = gasp::eval::NeesParts{6.0, 3.5, 2.5};
  run.nees_refinement = 900.0;
  gasp::pairs::PairsCsvChecks checks;
  checks.T_gt = pose(0.21, {0, 1, 0}, {0.1, -0.2, 0.31});
  checks.T_ref_icp = pose(0.205, {0, 1, 0}, {0.1, -0.2, 0.305});
  checks.T_est_icp = pose(0.2, {0, 1, 0}, {0.1, -0.2, 0.302});
  checks.rgb.ran = true;
  checks.rgb.inliers = 55;
  checks.rgb.R_rgb = pose(0.19, {0, 1, 0}, {0, 0, 0}).linear();
  checks.rgb.T_ref = pose(0.22, {0, 1, 0}, {0, 0, 0});
  checks.rgb.T_di_ri = checks.rgb.T_rj_dj = Isometry3::Identity();
  auto f = fieldsByName(gasp::pairs::pairsCsvRow(o, "gasp", run, checks));
  EXPECT_EQ(f["estimated"], "1");
  EXPECT_NEAR(number(f["t_err_m"]), 0.01, 1e-9);
  EXPECT_EQ(f["associations"], "120");
  EXPECT_EQ(f["inliers"], "80");
  EXPECT_NEAR(number(f["violation_ratio"]), 0.04, 1e-9);
  EXPECT_NEAR(number(f["violation_ratio_lesser"]), 0.01, 1e-9);
  EXPECT_NEAR(number(f["violation_blob_share_lesser"]), 0.25, 1e-9);
  EXPECT_NEAR(number(f["violation_blob_share"]), 0.5, 1e-9);
  EXPECT_NEAR(number(f["precision"]), 0.4, 1e-9);
  EXPECT_EQ(f["verified"], "150");
  EXPECT_NEAR(number(f["verified_precision"]), 140.0 / 150, 1e-5);
  EXPECT_NEAR(number(f["verified_density"]), 0.75, 1e-9);
  EXPECT_NEAR(number(f["tx"]), 0.1, 1e-9);
  EXPECT_NEAR(number(f["tz"]), 0.3, 1e-9);
  EXPECT_NEAR(std::abs(number(f["qy"])), std::sin(0.1), 1e-5);
  // Differences: A^-1 B of the two poses each column names.
  EXPECT_NEAR(number(f["ref_icp_t_m"]), 0.005, 1e-4);                                // truth vs polished truth
  EXPECT_NEAR(number(f["ref_icp_r_deg"]), 0.005 * 180 / M_PI, 1e-4);
  EXPECT_NEAR(number(f["est_vs_ref_icp_r_deg"]), 0.005 * 180 / M_PI, 1e-4);          // estimate vs polished truth
  EXPECT_NEAR(number(f["est_icp_t_m"]), 0.002, 1e-4);                                // estimate vs its own polish
  EXPECT_NEAR(number(f["icp_est_vs_ref_icp_t_m"]), 0.003, 1e-4);
  EXPECT_EQ(f["rgb_inliers"], "55");
  EXPECT_NEAR(number(f["rgb_r_vs_ref_deg"]), 0.03 * 180 / M_PI, 1e-4);               // images vs reference
  EXPECT_NEAR(number(f["rgb_r_vs_est_deg"]), 0.01 * 180 / M_PI, 1e-4);               // images vs estimate
  EXPECT_NEAR(number(f["rgb_r_vs_ref_icp_deg"]), 0.015 * 180 / M_PI, 1e-4);
  EXPECT_NEAR(number(f["nees_t"]), 3.5, 1e-9);
  EXPECT_NEAR(number(f["nees_refinement"]), 900.0, 1e-9);
  EXPECT_EQ(f["reason"], "");
}

TEST(PairReference, RollsTheTargetAndTurnsTheReferenceFrameBack) {
  const std::string dir = gasp::test::scratchDir();
  std::ofstream(dir + "/depth.txt") << "1.00 depth/1.png\n2.00 depth/2.png\n3.00 depth/3.png\n";
  const Isometry3 T0 = pose(0.3, {1, 2, 3}, {1, 2, 0.5}), T1 = pose(-0.2, {0, 1, 1}, {1.2, 1.9, 0.6});
  auto line = [](double t, const Isometry3& T) {
    const Eigen::Quaterniond q(T.linear());
    const auto& p = T.translation();
    char buf[256];
    std::snprintf(buf, sizeof buf, "%.4f %.9f %.9f %.9f %.12f %.12f %.12f %.12f\n", t, p.x(), p.y(), p.z(), q.x(),
                  q.y(), q.z(), q.w());
    return std::string(buf);
  };
  std::ofstream(dir + "/groundtruth.txt") << line(1.0, T0) << line(2.0, T1);  // frame 2 has none
  const auto ds = gasp::TumDataset::open(dir);
  auto near = [](const Isometry3& A, const Isometry3& B) { return (A.matrix() - B.matrix()).norm() < 1e-8; };

  const gasp::pairs::PairReference plain(ds, 0.0, Eigen::Vector3d::Zero(), 0);
  ASSERT_TRUE(plain.pair(0, 1));
  EXPECT_TRUE(near(*plain.pair(0, 1), T1.inverse() * T0));  // T_target_source: source 0, target 1
  EXPECT_FALSE(plain.pair(0, 2));                            // no ground truth for frame 2
  EXPECT_TRUE(plain.at(2.0) && near(*plain.at(2.0), T1));

  const gasp::pairs::PairReference rolled(ds, 0.0, Eigen::Vector3d::Zero(), 180);
  EXPECT_TRUE(near(*rolled.pair(0, 1), gasp::turnRotation(180) * T1.inverse() * T0));

  // The reference's camera is the depth camera turned by Q: the depth camera's pose is T Q^-1.
  const Eigen::Vector3d r(0.01, -0.02, 0.03);
  Isometry3 Q = Isometry3::Identity();
  Q.linear() = Eigen::AngleAxisd(r.norm(), r.normalized()).toRotationMatrix();
  const gasp::pairs::PairReference turned(ds, 0.0, r, 0);
  EXPECT_TRUE(near(*turned.frame(0), T0 * Q.inverse()));
  EXPECT_TRUE(near(*turned.pair(0, 1), Q * T1.inverse() * T0 * Q.inverse()));

  // The offset shifts the look-up: frame 0 at 1.0 + 1.0 s is T1's sample.
  const gasp::pairs::PairReference shifted(ds, 1.0, Eigen::Vector3d::Zero(), 0);
  EXPECT_TRUE(near(*shifted.frame(0), T1));
  EXPECT_FALSE(shifted.frame(1));
}

TEST(PairsTable, RowsHoldOnlyScoredSkipsAndCountThePairs) {
  gasp::pairs::PairsTally tally;
  for (std::size_t k = 0; k < 3; ++k) {
    gasp::eval::PairOutcome o;
    o.skip = 10, o.from = k, o.to = k + 10, o.ms = 100.0 + k;
    o.estimated = k != 1;
    o.t_err_m = 0.01, o.r_err_deg = 1.0;
    tally.by_method["gasp"].push_back(o);
  }
  tally.pairs_per_skip = {{10, 3}, {20, 0}};
  std::size_t total = 0;
  testing::internal::CaptureStdout();
  const auto rows = gasp::pairs::printPairsTable({10, 20}, {"gasp"}, tally, total);
  const std::string printed = testing::internal::GetCapturedStdout();
  ASSERT_EQ(rows.size(), 1u);  // skip 20 has no scored pair
  EXPECT_EQ(rows[0].pairs, 3u);
  EXPECT_EQ(rows[0].failed, 1u);
  EXPECT_EQ(total, 3u);
  EXPECT_NE(printed.find("20     gasp                0  no pair with ground truth for both frames"), std::string::npos)
      << printed;
  EXPECT_DOUBLE_EQ(gasp::pairs::median({3, 1, 2, 10}), 2.5);
  EXPECT_DOUBLE_EQ(gasp::pairs::median({}), 0.0);
}
