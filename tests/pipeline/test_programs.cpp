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
#include <sstream>
#include <vector>
#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>
#include <unistd.h>

#include "gasp/core/pose.h"
#include "gasp/core/tum_dataset.h"
#include "gasp_test_data.h"
#include "program_run.h"

namespace {

using gasp::test::ProgramRun;

ProgramRun run(const std::string& program, const std::string& args) {
  return gasp::test::runProgram(program, args);
}

/// A params file (docs/parameters.md) with `yaml` in it, in a folder of its own (scratchDir()
/// would empty the test's folder).
std::string paramsFile(const std::string& yaml) {
  static int n = 0;
  const std::string dir = std::string(GASP_TEST_TMP_DIR) + "/test_programs_params";
  std::filesystem::create_directories(dir);
  const std::string path = dir + "/" + std::to_string(::getpid()) + "_" + std::to_string(++n) + ".yaml";
  std::ofstream(path) << yaml;
  return path;
}

/// The cells of one CSV line (no quoting: the programs quote only the last column, `reason`).
std::vector<std::string> splitCsv(const std::string& line) {
  std::vector<std::string> cells;
  std::istringstream in(line);
  for (std::string cell; std::getline(in, cell, ',');) cells.push_back(cell);
  return cells;
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
  // The picture shows the verified associations, with their count and precision in its legend;
  // --free shows the free ones.
  ASSERT_TRUE(std::regex_search(r.output, m, std::regex("picture_legend: verified associations: ([0-9]+) -- [0-9]+ right, [0-9]+ wrong \\(precision [0-9.]+\\)")))
      << r.output;
  EXPECT_EQ(std::stod(m[1]), number(r.output, "verified_associations")) << r.output;
  const ProgramRun free = run("gasp-associate", "--tum " + dir + " --from 0 --to 4 --free --out " + out);
  ASSERT_EQ(free.exit_code, 0) << free.output;
  ASSERT_TRUE(std::regex_search(free.output, m, std::regex("picture_legend: free associations: ([0-9]+) -- "))) << free.output;
  EXPECT_EQ(std::stod(m[1]), number(free.output, "associations")) << free.output;
  // The edge information's standard deviations: no axis below the model error (1 cm, 0.75 deg).
  ASSERT_TRUE(std::regex_search(r.output, m, std::regex("edge_sigma: ([0-9.]+) ([0-9.]+) ([0-9.]+) m, ([0-9.]+) ([0-9.]+) ([0-9.]+) deg")))
      << r.output;
  for (int k = 1; k <= 3; ++k) EXPECT_GE(std::stod(m[k]), 0.0099) << r.output;
  for (int k = 4; k <= 6; ++k) EXPECT_GE(std::stod(m[k]), 0.74) << r.output;
  // The params file's certify.model_error_* set it; 0, 0 gives the refinement's (sub-millimetre) deviations.
  const ProgramRun none = run("gasp-associate", "--tum " + dir + " --from 0 --to 4 --params " +
                                                    paramsFile("certify:\n  model_error_t_m: 0\n  model_error_r_deg: 0\n"));
  ASSERT_EQ(none.exit_code, 0) << none.output;
  ASSERT_TRUE(std::regex_search(none.output, m, std::regex("edge_sigma: ([0-9.]+) ")));
  EXPECT_LT(std::stod(m[1]), 0.005) << none.output;
  const ProgramRun bad_error =
      run("gasp-associate", "--tum " + dir + " --from 0 --to 4 --params " + paramsFile("certify:\n  model_error_r_deg: -1\n"));
  EXPECT_EQ(bad_error.exit_code, 1) << bad_error.output;
  EXPECT_NE(bad_error.output.find("invalid parameters (certify.model_error_r_deg on line 2)"), std::string::npos)
      << bad_error.output;
  // refine.dense_line_search = false: no step is shortened and the rounds are never stopped by it.
  const ProgramRun plain = run("gasp-associate", "--tum " + dir + " --from 0 --to 4 --params " +
                                                     paramsFile("refine:\n  dense_line_search: false\n"));
  ASSERT_EQ(plain.exit_code, 0) << plain.output;
  EXPECT_TRUE(std::regex_search(plain.output, std::regex("dense_rounds: [0-9]+ \\(last step [0-9.]+ mm; line search: 0 steps shortened\\)\n")))
      << plain.output;
}

// --rawlog: two scans of an MRPT rawlog (fr1_desk9 converted by gasp-tum2rawlog) give the same
// pose as the TUM folder they came from, in camera and in robot frames, scored against the
// converter's camera trajectory; bad indices, a missing file and misplaced options are errors.
TEST(GaspAssociateProgram, TwoScansOfAnMrptRawlog) {
  GASP_REQUIRE_DATA(dir, "tum/fr1_desk9");
  const std::string scratch = gasp::test::scratchDir();
  const std::string rawlog = scratch + "/d9.rawlog";
  const ProgramRun convert = run("gasp-tum2rawlog", dir + " " + rawlog);
  ASSERT_EQ(convert.exit_code, 0) << convert.output;
  const ProgramRun r = run("gasp-associate", "--rawlog " + rawlog + " --from 0 --to 4 --gt " + scratch +
                                                 "/d9_groundtruth.txt --out " + scratch + "/r.png");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const ProgramRun t = run("gasp-associate", "--tum " + dir + " --from 0 --to 4 --out " + scratch + "/t.png");
  ASSERT_EQ(t.exit_code, 0) << t.output;
  std::smatch mr, mt;
  ASSERT_TRUE(std::regex_search(r.output, mr, std::regex("pose_T_b_a: ([^(]+)"))) << r.output;
  ASSERT_TRUE(std::regex_search(t.output, mt, std::regex("pose_T_b_a: ([^(]+)"))) << t.output;
  EXPECT_EQ(mr[1].str(), mt[1].str());  // the conversion keeps depth and intrinsics exactly
  ASSERT_TRUE(std::regex_search(r.output, mr, std::regex("pose_error: ([0-9.]+) m ([0-9.]+) deg"))) << r.output;
  EXPECT_LT(std::stod(mr[1]), 0.05);
  EXPECT_LT(std::stod(mr[2]), 3.0);
  EXPECT_GE(number(r.output, "precision"), 0.0) << r.output;
  // In robot frames (the converter mounts the camera looking along +X): the camera's z (forward)
  // translation is the robot's x.
  ASSERT_TRUE(std::regex_search(r.output, mr, std::regex("pose_robot_b_a: ([-0-9.]+) ([-0-9.]+) ([-0-9.]+) "))) << r.output;
  ASSERT_TRUE(std::regex_search(t.output, mt, std::regex("pose_T_b_a: ([-0-9.]+) ([-0-9.]+) ([-0-9.]+) "))) << t.output;
  EXPECT_EQ(mr[1].str(), mt[3].str());
  EXPECT_TRUE(std::filesystem::exists(scratch + "/r.png"));

  const ProgramRun far = run("gasp-associate", "--rawlog " + rawlog + " --from 0 --to 40");
  EXPECT_EQ(far.exit_code, 1);
  EXPECT_NE(far.output.find("has 9 CObservation3DRangeScan"), std::string::npos) << far.output;
  EXPECT_EQ(run("gasp-associate", "--rawlog " + scratch + "/missing.rawlog --from 0 --to 4").exit_code, 1);
  EXPECT_EQ(run("gasp-associate", "--from 0 --to 4").exit_code, 2);  // no source of views
  EXPECT_EQ(run("gasp-associate", "--tum " + dir + " --from 0 --to 4 --gt x.txt").exit_code, 2);  // --gt needs --rawlog
  EXPECT_EQ(run("gasp-associate", "--tum " + dir + " --rawlog " + rawlog + " --from 0 --to 4").exit_code, 2);
  EXPECT_EQ(run("gasp-associate", "--rawlog " + rawlog + " --to 4").exit_code, 2);  // both indices needed
  // --sensor counts only that sensor's scans: gasp-tum2rawlog labels them RGBD.
  const ProgramRun labelled = run("gasp-associate", "--rawlog " + rawlog + " --sensor RGBD --from 0 --to 4 --out " + scratch + "/s.png");
  ASSERT_EQ(labelled.exit_code, 0) << labelled.output;
  ASSERT_TRUE(std::regex_search(labelled.output, mr, std::regex("pose_T_b_a: ([^(]+)"))) << labelled.output;
  ASSERT_TRUE(std::regex_search(t.output, mt, std::regex("pose_T_b_a: ([^(]+)"))) << t.output;
  EXPECT_EQ(mr[1].str(), mt[1].str());
  const ProgramRun other = run("gasp-associate", "--rawlog " + rawlog + " --sensor KINECT2 --from 0 --to 4");
  EXPECT_EQ(other.exit_code, 1);
  EXPECT_NE(other.output.find("has 0 CObservation3DRangeScan of sensor 'KINECT2'"), std::string::npos) << other.output;
  EXPECT_EQ(run("gasp-associate", "--rawlog " + rawlog + " --from 0 --to 4 --intrinsics fr1").exit_code, 2);  // the scans carry theirs
}

// --rolling-shutter: both views deskewed with their neighbours' velocity, said on two lines;
// the pose moves. The first frame has a neighbour on one side only; PNGs have none (usage error).
TEST(GaspAssociateProgram, RollingShutterDeskewsBothViews) {
  GASP_REQUIRE_DATA(dir, "tum/fr1_desk9");
  const std::string scratch = gasp::test::scratchDir();
  const ProgramRun plain = run("gasp-associate", "--tum " + dir + " --from 0 --to 4 --out " + scratch + "/a.png");
  const ProgramRun r = run("gasp-associate", "--tum " + dir + " --from 0 --to 4 --rolling-shutter 0.03 --out " + scratch + "/b.png");
  ASSERT_EQ(plain.exit_code, 0) << plain.output;
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(plain.output.find("rolling_shutter"), std::string::npos);
  EXPECT_TRUE(std::regex_search(r.output, std::regex("rolling_shutter_a: deskewed, velocity [0-9.]+ m/s [0-9.]+ deg/s \\(frames 0 -> 1\\)"))) << r.output;
  EXPECT_TRUE(std::regex_search(r.output, std::regex("rolling_shutter_b: deskewed, velocity [0-9.]+ m/s [0-9.]+ deg/s \\(frames 3 -> 5\\)"))) << r.output;
  std::smatch m_plain, m;
  ASSERT_TRUE(std::regex_search(plain.output, m_plain, std::regex("pose_T_b_a: ([^(]+)")));
  ASSERT_TRUE(std::regex_search(r.output, m, std::regex("pose_T_b_a: ([^(]+)")));
  EXPECT_NE(m_plain[1].str(), m[1].str());
  EXPECT_LT(number(r.output, "pose_error"), 0.05) << r.output;
  EXPECT_EQ(run("gasp-associate", "--tum " + dir + " --from 0 --to 4 --rolling-shutter nan").exit_code, 2);
  EXPECT_EQ(run("gasp-associate", "--depth-a a.png --depth-b b.png --rolling-shutter 0.03").exit_code, 2);
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
  // The picture's folder is checked before the work; a bad range is a usage error, said as one.
  const ProgramRun no_folder = run("gasp-associate", "--depth-a " + pngs[0] + " --depth-b " + pngs[1] + " --out /nonexistent-dir/a.png");
  EXPECT_EQ(no_folder.exit_code, 1) << no_folder.output;
  EXPECT_NE(no_folder.output.find("does not exist"), std::string::npos) << no_folder.output;
  EXPECT_EQ(no_folder.output.find("patches_a"), std::string::npos) << no_folder.output;
  // The default picture path (associations.png in the working folder) is checked the same way.
  const std::string cwd = gasp::test::scratchDir() + "/default_out";
  std::filesystem::create_directories(cwd + "/associations.png");
  const ProgramRun default_out = gasp::test::runProgram(
      "gasp-associate", "--depth-a " + pngs[0] + " --depth-b " + pngs[1] + " --intrinsics fr1", "&1", cwd);
  EXPECT_EQ(default_out.exit_code, 1) << default_out.output;
  EXPECT_NE(default_out.output.find("'associations.png': is a folder"), std::string::npos) << default_out.output;
  EXPECT_EQ(default_out.output.find("patches_a"), std::string::npos) << default_out.output;
  // segment.target_patch_area_m2: larger patches, fewer of them; 0 is an error naming the key.
  const auto patchesA = [](const std::string& output) {
    const auto pos = output.find("patches_a: ");
    return pos == std::string::npos ? -1 : std::stoi(output.substr(pos + 11));
  };
  const ProgramRun large = run("gasp-associate", "--depth-a " + pngs[0] + " --depth-b " + pngs[1] + " --intrinsics fr1 --params " +
                                                     paramsFile("segment:\n  target_patch_area_m2: 0.008\n") + " --out " + out);
  EXPECT_EQ(large.exit_code, 0) << large.output;
  EXPECT_GT(patchesA(large.output), 0) << large.output;
  EXPECT_LT(patchesA(large.output), patchesA(ok.output)) << large.output << ok.output;
  const ProgramRun no_area = run("gasp-associate", "--depth-a " + pngs[0] + " --depth-b " + pngs[1] + " --params " +
                                                       paramsFile("segment:\n  target_patch_area_m2: 0\n"));
  EXPECT_EQ(no_area.exit_code, 1) << no_area.output;
  EXPECT_NE(no_area.output.find("(segment.target_patch_area_m2 on line 2)"), std::string::npos) << no_area.output;
  const ProgramRun bad_k = run("gasp-associate", "--depth-a " + pngs[0] + " --depth-b " + pngs[1] + " --params " +
                                                     paramsFile("associate:\n  neighbourhood_k: -1\n"));
  EXPECT_EQ(bad_k.exit_code, 1) << bad_k.output;
  EXPECT_NE(bad_k.output.find("(associate.neighbourhood_k on line 2)"), std::string::npos) << bad_k.output;
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
  EXPECT_EQ(run("gasp-pairs", "--tum " + dir + " --skips 1 --depth-scale 0").exit_code, 2);  // usage error
  EXPECT_EQ(run("gasp-pairs", "--tum " + dir + " --skips 1 --depth-scale -5000").exit_code, 2);
  // The dense rounds' parameters: an error naming the key before any pair, NaN and negatives alike.
  for (const std::string key : {"refine.dense_extrapolation_max: nan", "refine.dense_extrapolation_max: -1",
                                "refine.dense_max_rounds: -2", "refine.wide_edge_gate_factor: inf",
                                "refine.wide_edge_gate_factor: 0.5", "retry.retry_area_factor: 0.005",
                                "retry.retry_area_factor: 1", "refine.projective_pixel_step: 0",
                                "refine.edge_weight: -1", "refine.edge_pixel_step: 0"}) {
    const std::string section = key.substr(0, key.find('.')), value = key.substr(key.find('.') + 1);
    const ProgramRun bad =
        run("gasp-pairs", "--tum " + dir + " --skips 1 --params " + paramsFile(section + ":\n  " + value + "\n"));
    EXPECT_EQ(bad.exit_code, 1) << key << ": " << bad.output;
    EXPECT_NE(bad.output.find("error: params '"), std::string::npos) << key << ": " << bad.output;
    EXPECT_NE(bad.output.find(key.substr(0, key.find(':'))), std::string::npos) << key << ": " << bad.output;
    EXPECT_EQ(bad.output.find("pair 1/"), std::string::npos) << key << ": " << bad.output;
  }
#ifdef GASP_HAVE_BASELINES
  for (const std::string option : {"--ratio 0", "--ratio 1.5", "--min-keypoints -5"}) {
    const ProgramRun bad = run("gasp-pairs", "--tum " + dir + " --skips 1 " + option);
    EXPECT_EQ(bad.exit_code, 2) << option << ": " << bad.output;
    EXPECT_NE(bad.output.find("error: --"), std::string::npos) << option << ": " << bad.output;
    EXPECT_NE(bad.output.find("must be"), std::string::npos) << option << ": " << bad.output;
  }
#endif
  // A missing output folder is bad input, said before any pair runs.
  const ProgramRun no_folder = run("gasp-pairs", "--tum " + dir + " --skips 1 --csv /nonexistent-dir/t.csv");
  EXPECT_EQ(no_folder.exit_code, 1) << no_folder.output;
  EXPECT_NE(no_folder.output.find("does not exist"), std::string::npos) << no_folder.output;
  EXPECT_EQ(no_folder.output.find("pair 1/"), std::string::npos) << no_folder.output;
  // So are the pictures' paths (one per method that draws).
  const ProgramRun no_picture_folder =
      run("gasp-pairs", "--tum " + dir + " --skips 1 --picture 0,1 --picture-prefix /nonexistent-dir/p_");
  EXPECT_EQ(no_picture_folder.exit_code, 1) << no_picture_folder.output;
  EXPECT_NE(no_picture_folder.output.find("--picture-prefix '/nonexistent-dir/p_gasp.png': the folder"),
            std::string::npos)
      << no_picture_folder.output;
  EXPECT_EQ(no_picture_folder.output.find("pair 1/"), std::string::npos) << no_picture_folder.output;
}

// The dense rounds' line search: its two pairs-CSV columns, and the flag that turns it off.
TEST(GaspPairsProgram, DenseLineSearchColumnsAndFlag) {
  GASP_REQUIRE_DATA(dir, "tum/fr1_desk9");
  const std::string scratch = gasp::test::scratchDir();
  const std::string args = "--tum " + dir + " --skips 2 --starts-every 3 --max-pairs 2 --method gasp --pairs-csv ";
  for (const std::string& flag : {std::string(), " --params " + paramsFile("refine:\n  dense_line_search: false\n")}) {
    const ProgramRun r = run("gasp-pairs", args + scratch + "/ls.csv" + flag);
    ASSERT_EQ(r.exit_code, 0) << flag << ": " << r.output;
    std::ifstream f(scratch + "/ls.csv");
    std::string header, line;
    std::getline(f, header);
    const auto names = splitCsv(header);
    const auto column = [&](const std::string& name) {
      const auto it = std::find(names.begin(), names.end(), name);
      return it == names.end() ? -1 : static_cast<int>(it - names.begin());
    };
    const int shortened = column("dense_shortened"), stopped = column("dense_stopped");
    ASSERT_GE(shortened, 0) << header;
    ASSERT_EQ(stopped, shortened + 1) << header;
    EXPECT_EQ(column("dense_last_step_m"), shortened - 1) << header;
    int rows = 0;
    while (std::getline(f, line)) {
      const auto cells = splitCsv(line);
      ASSERT_GT(cells.size(), static_cast<std::size_t>(stopped)) << line;
      EXPECT_GE(std::stoi(cells[static_cast<std::size_t>(shortened)]), 0) << line;
      EXPECT_TRUE(cells[static_cast<std::size_t>(stopped)] == "0" || cells[static_cast<std::size_t>(stopped)] == "1") << line;
      if (!flag.empty()) {
        EXPECT_EQ(cells[static_cast<std::size_t>(shortened)], "0") << line;
        EXPECT_EQ(cells[static_cast<std::size_t>(stopped)], "0") << line;
      }
      ++rows;
    }
    EXPECT_EQ(rows, 2) << flag;
  }
}

// --rolling-shutter: every GASP frame is deskewed with its neighbours' velocity (or the
// reference's), which moves the estimate; bad values are usage errors.
TEST(GaspPairsProgram, RollingShutterDeskewsEachFrame) {
  GASP_REQUIRE_DATA(dir, "tum/fr1_desk9");
  const std::string scratch = gasp::test::scratchDir();
  const std::string args = "--tum " + dir + " --skips 2 --starts-every 3 --method gasp --pairs-csv ";
  const ProgramRun plain = run("gasp-pairs", args + scratch + "/plain.csv");
  ASSERT_EQ(plain.exit_code, 0) << plain.output;
  EXPECT_EQ(plain.output.find("rolling_shutter:"), std::string::npos) << plain.output;
  const ProgramRun deskewed = run("gasp-pairs", args + scratch + "/deskewed.csv --rolling-shutter 0.03");
  ASSERT_EQ(deskewed.exit_code, 0) << deskewed.output;
  // Pairs 0->2, 3->5, 6->8: six frames, each with a neighbour on at least one side.
  EXPECT_NE(deskewed.output.find("rolling_shutter: readout 0.0300 s, velocity from neighbours, 6 of 6 frames deskewed"),
            std::string::npos)
      << deskewed.output;
  const ProgramRun truth = run("gasp-pairs", args + scratch + "/truth.csv --rolling-shutter 0.03 --twist-from truth");
  ASSERT_EQ(truth.exit_code, 0) << truth.output;
  EXPECT_NE(truth.output.find("velocity from truth, 6 of 6 frames deskewed"), std::string::npos) << truth.output;

  // The deskew moves the poses (by a little: fr1_desk9 moves slowly); the columns tx..qw.
  auto poses = [](const std::string& path) {
    std::ifstream f(path);
    std::string line;
    std::getline(f, line);
    const auto header = splitCsv(line);
    const auto first = std::find(header.begin(), header.end(), "tx") - header.begin();
    std::vector<std::vector<std::string>> rows;
    while (std::getline(f, line)) {
      const auto c = splitCsv(line);
      rows.emplace_back(c.begin() + first, c.begin() + first + 7);
    }
    return rows;
  };
  const auto a = poses(scratch + "/plain.csv"), b = poses(scratch + "/deskewed.csv");
  ASSERT_EQ(a.size(), 3u);
  ASSERT_EQ(b.size(), 3u);
  int moved = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_FALSE(a[i][0].empty());  // an estimate
    moved += a[i] != b[i];
  }
  EXPECT_GE(moved, 2);

  EXPECT_EQ(run("gasp-pairs", "--tum " + dir + " --skips 2 --rolling-shutter nan").exit_code, 2);
  EXPECT_EQ(run("gasp-pairs", "--tum " + dir + " --skips 2 --rolling-shutter 0.03 --twist-from imu").exit_code, 2);
  EXPECT_EQ(run("gasp-pairs", "--tum " + dir + " --skips 2 --twist-from truth").exit_code, 2);  // needs --rolling-shutter
}

// --roll-target: each pair's target image turned by a half or quarter turn (the camera rolled
// about its optical axis) is registered as well as the upright one, against the reference rolled
// alike; a roll left out of the reference would be an error of 90-180 deg.
TEST(GaspPairsProgram, RollTargetTurnsTheTargetViewAndItsReference) {
  GASP_REQUIRE_DATA(dir, "tum/fr1_desk9");
  const std::string scratch = gasp::test::scratchDir();
  const std::string args = "--tum " + dir + " --skips 2 --starts-every 3 --method gasp --pairs-csv ";
  for (const int deg : {0, 90, 180, 270}) {
    const std::string csv = scratch + "/roll" + std::to_string(deg) + ".csv";
    const ProgramRun r = run("gasp-pairs", args + csv + " --roll-target " + std::to_string(deg));
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_EQ(r.output.find("roll_target: " + std::to_string(deg) + " deg") != std::string::npos, deg != 0) << r.output;
    std::ifstream f(csv);
    std::string line;
    std::getline(f, line);
    const auto header = splitCsv(line);
    const auto col = [&](const std::string& name) {
      return static_cast<std::size_t>(std::find(header.begin(), header.end(), name) - header.begin());
    };
    int rows = 0;
    while (std::getline(f, line)) {
      const auto c = splitCsv(line);
      ++rows;
      ASSERT_EQ(c[col("estimated")], "1") << deg << ": " << line;
      EXPECT_LT(std::stod(c[col("t_err_m")]), 0.03) << deg << ": " << line;
      EXPECT_LT(std::stod(c[col("r_err_deg")]), 2.0) << deg << ": " << line;
      // The estimate holds the roll: its rotation angle is about the turn (fr1_desk9 moves little).
      const double qw = std::abs(std::stod(c[col("qw")]));
      EXPECT_NEAR(2.0 * std::acos(std::min(qw, 1.0)) * 180.0 / M_PI, deg == 270 ? 90.0 : deg, 10.0) << deg << ": " << line;
    }
    EXPECT_EQ(rows, 3) << deg;
  }
  EXPECT_EQ(run("gasp-pairs", "--tum " + dir + " --skips 2 --roll-target 45").exit_code, 2);
#ifdef GASP_HAVE_BASELINES
  for (const std::string& extra : std::vector<std::string>{"--method gasp,gicp", "--method gasp,sift", "--polish-reference --pairs-csv " + scratch + "/p.csv"}) {
    const ProgramRun r = run("gasp-pairs", "--tum " + dir + " --skips 2 --roll-target 180 " + extra);
    EXPECT_EQ(r.exit_code, 2) << extra << ": " << r.output;
    EXPECT_NE(r.output.find("--roll-target: "), std::string::npos) << extra << ": " << r.output;
  }
#endif
}

// --reverse: each pair registered the other way round (frame I+skip onto frame I, as the
// odometry registers a frame to its keyframe), scored against the inverse reference: the two
// directions' estimates are each other's inverse within a centimetre and a degree; with
// --roll-target the turned view is frame I.
TEST(GaspPairsProgram, ReverseRegistersEachPairTheOtherWayRound) {
  GASP_REQUIRE_DATA(dir, "tum/fr1_desk9");
  const std::string scratch = gasp::test::scratchDir();
  const std::string args = "--tum " + dir + " --skips 2 --starts-every 3 --method gasp --pairs-csv ";
  const auto poses = [](const std::string& csv) {
    std::ifstream f(csv);
    std::string line;
    std::getline(f, line);
    const auto header = splitCsv(line);
    const auto col = [&](const std::string& name) {
      return static_cast<std::size_t>(std::find(header.begin(), header.end(), name) - header.begin());
    };
    std::vector<std::pair<gasp::Isometry3, std::pair<double, double>>> out;  // estimate, (t_err, r_err)
    while (std::getline(f, line)) {
      const auto c = splitCsv(line);
      if (c[col("estimated")] != "1") continue;
      gasp::Isometry3 T = gasp::Isometry3::Identity();
      T.linear() = Eigen::Quaterniond(std::stod(c[col("qw")]), std::stod(c[col("qx")]), std::stod(c[col("qy")]),
                                      std::stod(c[col("qz")]))
                       .normalized()
                       .toRotationMatrix();
      T.translation() << std::stod(c[col("tx")]), std::stod(c[col("ty")]), std::stod(c[col("tz")]);
      out.push_back({T, {std::stod(c[col("t_err_m")]), std::stod(c[col("r_err_deg")])}});
    }
    return out;
  };
  ProgramRun r = run("gasp-pairs", args + scratch + "/fwd.csv");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(r.output.find("direction: reversed"), std::string::npos) << r.output;
  r = run("gasp-pairs", args + scratch + "/rev.csv --reverse");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("direction: reversed (each pair's frame I+skip registered onto frame I)"), std::string::npos)
      << r.output;
  const auto fwd = poses(scratch + "/fwd.csv"), rev = poses(scratch + "/rev.csv");
  ASSERT_EQ(fwd.size(), 3u);
  ASSERT_EQ(rev.size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_LT(rev[k].second.first, 0.03) << k;
    EXPECT_LT(rev[k].second.second, 2.0) << k;
    const gasp::Isometry3 loop = fwd[k].first * rev[k].first;  // T_j_i T_i_j
    EXPECT_LT(loop.translation().norm(), 0.01) << k;
    EXPECT_LT(Eigen::AngleAxisd(loop.rotation()).angle() * 180.0 / M_PI, 1.0) << k;
    // Not the same pose twice: fr1_desk9 moves a few centimetres between the frames.
    EXPECT_GT((fwd[k].first.translation() - rev[k].first.translation()).norm(), 0.5 * fwd[k].first.translation().norm())
        << k;
  }
  // With the roll, frame I is turned: still scored against the matching reference.
  r = run("gasp-pairs", args + scratch + "/rev180.csv --reverse --roll-target 180");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto rolled = poses(scratch + "/rev180.csv");
  ASSERT_EQ(rolled.size(), 3u);
  for (const auto& [T, err] : rolled) {
    EXPECT_LT(err.first, 0.03);
    EXPECT_LT(err.second, 2.0);
    EXPECT_NEAR(Eigen::AngleAxisd(T.rotation()).angle() * 180.0 / M_PI, 180.0, 10.0);
  }
#ifdef GASP_HAVE_BASELINES
  r = run("gasp-pairs", "--tum " + dir + " --skips 2 --reverse --rgb-rotation-check --pairs-csv " + scratch + "/x.csv");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--reverse: not with --rgb-rotation-check"), std::string::npos) << r.output;
#endif
}

TEST(GaspPairsProgram, GtFrameRotationTurnsTheReferenceBack) {
  // --gt-frame-rotation r: the reference's camera frame taken as turned by exp(r) and turned back
  // before scoring. Zero changes nothing; a few degrees change every pair's error but not the
  // estimates; a rotation needs three finite angles.
  GASP_REQUIRE_DATA(dir, "tum/fr1_desk9");
  const std::string scratch = gasp::test::scratchDir();
  const std::string args = "--tum " + dir + " --skips 2 --starts-every 3 --method gasp --pairs-csv ";
  auto column = [](const std::string& path, const std::string& name) {
    std::ifstream f(path);
    std::string line;
    std::getline(f, line);
    const auto header = splitCsv(line);
    const auto k = std::find(header.begin(), header.end(), name) - header.begin();
    std::vector<std::string> out;
    while (std::getline(f, line)) out.push_back(splitCsv(line)[static_cast<std::size_t>(k)]);
    return out;
  };
  ASSERT_EQ(run("gasp-pairs", args + scratch + "/plain.csv").exit_code, 0);
  ASSERT_EQ(run("gasp-pairs", args + scratch + "/zero.csv --gt-frame-rotation 0,0,0").exit_code, 0);
  const ProgramRun turned = run("gasp-pairs", args + scratch + "/turned.csv --gt-frame-rotation 3,0,-2");
  ASSERT_EQ(turned.exit_code, 0) << turned.output;
  EXPECT_EQ(column(scratch + "/plain.csv", "r_err_deg"), column(scratch + "/zero.csv", "r_err_deg"));
  EXPECT_EQ(column(scratch + "/plain.csv", "qw"), column(scratch + "/turned.csv", "qw"));  // same estimates
  const auto a = column(scratch + "/plain.csv", "r_err_deg"), b = column(scratch + "/turned.csv", "r_err_deg");
  ASSERT_EQ(a.size(), 3u);
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_NE(a[i], b[i]) << "pair " << i;
  EXPECT_EQ(run("gasp-pairs", "--tum " + dir + " --skips 2 --gt-frame-rotation 3,0").exit_code, 2);
  EXPECT_EQ(run("gasp-pairs", "--tum " + dir + " --skips 2 --gt-frame-rotation 3,0,nan").exit_code, 2);
}

// The params file's certify.model_error_* set the model error of the edge information the nees
// columns are scored under: with none, the edge information is the refinement's (nees =
// nees_refinement); with the default it is less certain (nees < nees_refinement); a negative or
// malformed value is an error naming the key.
TEST(GaspPairsProgram, ModelErrorSetsTheEdgeInformation) {
  GASP_REQUIRE_DATA(dir, "tum/fr1_desk9");
  const std::string scratch = gasp::test::scratchDir();
  const std::string args = "--tum " + dir + " --skips 2 --starts-every 3 --method gasp --pairs-csv ";
  auto columns = [](const std::string& path, const std::string& a, const std::string& b) {
    std::ifstream f(path);
    std::string line;
    std::getline(f, line);
    const auto header = splitCsv(line);
    const auto ka = static_cast<std::size_t>(std::find(header.begin(), header.end(), a) - header.begin());
    const auto kb = static_cast<std::size_t>(std::find(header.begin(), header.end(), b) - header.begin());
    std::vector<std::pair<double, double>> out;
    while (std::getline(f, line)) {
      const auto c = splitCsv(line);
      out.emplace_back(std::stod(c.at(ka)), std::stod(c.at(kb)));
    }
    return out;
  };
  ASSERT_EQ(run("gasp-pairs", args + scratch + "/none.csv --params " +
                                   paramsFile("certify:\n  model_error_t_m: 0\n  model_error_r_deg: 0\n"))
                .exit_code,
            0);
  ASSERT_EQ(run("gasp-pairs", args + scratch + "/default.csv").exit_code, 0);
  const auto none = columns(scratch + "/none.csv", "nees", "nees_refinement");
  const auto dflt = columns(scratch + "/default.csv", "nees", "nees_refinement");
  ASSERT_EQ(none.size(), 3u);
  ASSERT_EQ(dflt.size(), 3u);
  for (std::size_t i = 0; i < none.size(); ++i) {
    EXPECT_NEAR(none[i].first, none[i].second, 1e-4 * none[i].second) << "pair " << i;
    EXPECT_NEAR(dflt[i].second, none[i].second, 1e-4 * none[i].second) << "pair " << i;  // same poses
    EXPECT_LT(dflt[i].first, 0.1 * dflt[i].second) << "pair " << i;
  }
  EXPECT_EQ(run("gasp-pairs", "--tum " + dir + " --skips 2 --params " + paramsFile("certify:\n  model_error_t_m: -0.01\n"))
                .exit_code,
            1);
  EXPECT_EQ(run("gasp-pairs", "--tum " + dir + " --skips 2 --params " + paramsFile("certify:\n  model_error_t_m: 0.01,0.75\n"))
                .exit_code,
            1);
}

// The per-pair CSV: one row per pair with the estimated pose, whose error against the ground truth
// is the row's own t_err_m / r_err_deg, and the free and verified associations scored.
TEST(GaspPairsProgram, PairsCsvHasThePoseAndTheAssociationQuality) {
  GASP_REQUIRE_DATA(dir, "tum/fr1_desk9");
  const std::string pairs = gasp::test::scratchDir() + "/pairs.csv";
  const ProgramRun r = run("gasp-pairs", "--tum " + dir + " --skips 1,4 --starts-every 4 --method gasp --pairs-csv " + pairs);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::ifstream f(pairs);
  std::string line;
  std::getline(f, line);
  const auto header = splitCsv(line);
  auto col = [&](const std::string& name) {
    const auto it = std::find(header.begin(), header.end(), name);
    EXPECT_NE(it, header.end()) << name;
    return static_cast<std::size_t>(it - header.begin());
  };
  const auto ds = gasp::TumDataset::open(dir);
  int rows = 0;
  while (std::getline(f, line)) {
    ++rows;
    const auto c = splitCsv(line);
    ASSERT_GE(c.size(), header.size() - 1) << line;  // the reason may be empty
    const std::size_t from = std::stoul(c[col("from")]), to = std::stoul(c[col("to")]);
    ASSERT_EQ(c[col("estimated")], "1") << line;  // fr1_desk9's pairs are easy
    const Eigen::Quaterniond q(std::stod(c[col("qw")]), std::stod(c[col("qx")]), std::stod(c[col("qy")]),
                               std::stod(c[col("qz")]));
    EXPECT_NEAR(q.norm(), 1.0, 1e-4) << line;
    gasp::Isometry3 T = gasp::Isometry3::Identity();
    T.linear() = q.normalized().toRotationMatrix();
    T.translation() = Eigen::Vector3d(std::stod(c[col("tx")]), std::stod(c[col("ty")]), std::stod(c[col("tz")]));
    const gasp::Isometry3 T_true = gasp::relativePose(*ds.groundTruthOf(to), *ds.groundTruthOf(from));
    const gasp::Isometry3 E = T_true.inverse() * T;
    EXPECT_NEAR(gasp::translationNorm(E), std::stod(c[col("t_err_m")]), 2e-4) << line;
    EXPECT_NEAR(gasp::rotationAngle(E) * 180.0 / M_PI, std::stod(c[col("r_err_deg")]), 0.02) << line;
    const double precision = std::stod(c[col("precision")]);
    const double verified_precision = std::stod(c[col("verified_precision")]);
    EXPECT_GE(precision, 0.0);
    EXPECT_LE(precision, 1.0);
    EXPECT_GT(std::stoi(c[col("verified")]), 20) << line;
    EXPECT_GT(verified_precision, 0.5) << line;  // close frames with a pose within a few mm
    EXPECT_LE(verified_precision, 1.0);
    EXPECT_GT(std::stod(c[col("verified_density")]), 0.3) << line;
    // The share of depth samples each pose puts on the other view's surface (tight gate): the
    // estimate's is high on these easy pairs; the ground truth's is a share too.
    EXPECT_GT(std::stod(c[col("agreement")]), 0.9) << line;
    const double agreement_truth = std::stod(c[col("agreement_truth")]);
    EXPECT_GT(agreement_truth, 0.0) << line;
    EXPECT_LE(agreement_truth, 1.0) << line;
    // The pair's true motion: fr1_desk9 moves a few cm and degrees between these frames.
    EXPECT_NEAR(std::stod(c[col("motion_t_m")]), gasp::translationNorm(T_true), 1e-4) << line;
    EXPECT_NEAR(std::stod(c[col("motion_r_deg")]), gasp::rotationAngle(T_true) * 180.0 / M_PI, 0.01) << line;
    // The error's NEES under the claimed information: a finite, positive number for an estimate
    // (pose_consistency.h; its size is measured in docs/pipeline.md).
    const double nees = std::stod(c[col("nees")]);
    EXPECT_TRUE(std::isfinite(nees)) << line;
    EXPECT_GT(nees, 0.0) << line;
  }
  EXPECT_EQ(rows, 4);  // 0->1, 4->5, 0->4, 4->8
}
