// End-to-end checks of gasp-associate and gasp-pairs on real data (skipped without it): output
// lines, the picture, exit codes; the numbers are checked loosely (the benchmark docs hold the
// measured figures).
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <regex>
#include <vector>
#include <algorithm>

#include "gasp_test_data.h"
#include "program_run.h"

namespace {

using gasp::test::ProgramRun;

ProgramRun run(const std::string& program, const std::string& args) {
  return gasp::test::runProgram(program, args);
}

double number(const std::string& text, const std::string& key) {
  std::smatch m;
  if (!std::regex_search(text, m, std::regex(key + ":? ([-0-9.e+]+)"))) return -1.0;
  return std::stod(m[1]);
}

}  // namespace

TEST(GaspAssociateProgram, PoseAndPictureOnARealPair) {
  GASP_REQUIRE_DATA(dir, "tum/fr1_desk9");
  const std::string out = gasp::test::scratchDir() + "/pair.png";
  const ProgramRun r = run("gasp-associate", "--tum " + dir + " --from 0 --to 4 --out " + out);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_GT(number(r.output, "patches_a"), 100) << r.output;
  EXPECT_GT(number(r.output, "associations"), 20) << r.output;
  EXPECT_GE(number(r.output, "precision"), 0.0) << r.output;
  EXPECT_NE(r.output.find("pose_T_b_a:"), std::string::npos);
  std::smatch m;
  ASSERT_TRUE(std::regex_search(r.output, m, std::regex("pose_error: ([0-9.]+) m ([0-9.]+) deg"))) << r.output;
  EXPECT_LT(std::stod(m[1]), 0.05) << r.output;
  EXPECT_LT(std::stod(m[2]), 3.0) << r.output;
  EXPECT_TRUE(std::filesystem::exists(out));
}

TEST(GaspAssociateProgram, TwoPngsAndExitCodes) {
  GASP_REQUIRE_DATA(dir, "tum/fr1_desk9");
  std::vector<std::string> pngs;
  for (const auto& e : std::filesystem::directory_iterator(dir + "/depth")) pngs.push_back(e.path().string());
  std::sort(pngs.begin(), pngs.end());
  ASSERT_GE(pngs.size(), 2u);
  const std::string out = gasp::test::scratchDir() + "/pngs.png";
  const ProgramRun ok = run("gasp-associate", "--depth-a " + pngs[0] + " --depth-b " + pngs[1] + " --intrinsics fr1 --out " + out);
  EXPECT_EQ(ok.exit_code, 0) << ok.output;
  EXPECT_NE(ok.output.find("ground truth: not available"), std::string::npos);
  EXPECT_EQ(run("gasp-associate", "--depth-a /nonexistent.png --depth-b " + pngs[1]).exit_code, 1);
  EXPECT_EQ(run("gasp-associate", "--from 0").exit_code, 2);
  // The same view twice at an all-zero depth: no patches, no associations.
  const std::string zero = gasp::test::scratchDir() + "/zero.png";
  {
    std::ofstream f(zero);  // not a PNG: a clear error, exit 1
  }
  EXPECT_EQ(run("gasp-associate", "--depth-a " + zero + " --depth-b " + zero).exit_code, 1);
}

TEST(GaspPairsProgram, TableAndCsvOnARealFolder) {
  GASP_REQUIRE_DATA(dir, "tum/fr1_desk9");
  const std::string csv = gasp::test::scratchDir() + "/table.csv";
  const ProgramRun r = run("gasp-pairs", "--tum " + dir + " --skips 1,2 --starts-every 3 --method gasp,gasp-norefine --csv " + csv);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("median_ms_per_stage gasp:"), std::string::npos) << r.output;
  std::ifstream f(csv);
  std::string header, line;
  std::getline(f, header);
  EXPECT_EQ(header, "skip,method,pairs,failed,rmse_t_m,rmse_r_deg,fail_pct,within_5cm_2deg_pct,median_ms");
  int rows = 0;
  while (std::getline(f, line)) {
    ++rows;
    EXPECT_TRUE(line.rfind("1,", 0) == 0 || line.rfind("2,", 0) == 0) << line;
  }
  EXPECT_EQ(rows, 4);  // 2 skips x 2 methods
  EXPECT_EQ(run("gasp-pairs", "--tum /nonexistent").exit_code, 1);
  EXPECT_EQ(run("gasp-pairs", "--tum " + dir + " --skips 100").exit_code, 4);  // no pair
}
