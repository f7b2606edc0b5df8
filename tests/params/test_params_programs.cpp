// Every program: --params FILE loads a params file, --print-params writes the effective values
// (defaults < file < the program's own options) as a file that loads back to the same values,
// and a bad params file is an error naming the file, the line and the key (exit 1).
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "gasp/params/params_file.h"
#include "gasp_test_data.h"
#include "program_run.h"

namespace {

using gasp::test::contains;
using gasp::test::runProgram;

const char* const kPrograms[] = {"gasp-simulate", "gasp-tum2rawlog", "gasp-rawlog2tum", "gasp-eval",
                                 "gasp-segment",  "gasp-associate",  "gasp-pairs",      "gasp-pairs-plot",
                                 "gasp-odometry", "gasp-slam",       "gasp-graphslam",  "gasp-loops"};

/// A params file with a value changed in every section.
const char* const kChanged =
    "segment:\n  target_patch_area_m2: 0.005\n"
    "associate:\n  lambda: 0.65\n  candidate_key: mean\n"
    "hypothesise:\n  min_inliers: 9\n"
    "refine:\n  dense_gates_m: [0.12, 0.04]\n"
    "certify:\n  visibility_max_occluded_ratio: 0.45\n"
    "retry:\n  retry_area_factor: 0.25\n"
    "odometry:\n  keyframe_angle_deg: 7.5\n"
    "loop_closure:\n  loop_min_inliers: 25\n"
    "pose_graph:\n  function_tolerance: 1e-12\n";

std::string write(const std::string& path, const std::string& text) {
  std::ofstream(path) << text;
  return path;
}

gasp::SlamParams changed() { return gasp::readParamsYaml(kChanged, "changed"); }

}  // namespace

TEST(ParamsPrograms, PrintParamsLoadsBackUnchangedInEveryProgram) {
  const std::string dir = gasp::test::scratchDir();
  const std::string file = write(dir + "/changed.yaml", kChanged);
  for (const std::string program : kPrograms) {
    // The defaults, without any input.
    const auto defaults = runProgram(program, "--print-params", "/dev/null");
    ASSERT_EQ(defaults.exit_code, 0) << program << ": " << defaults.output;
    EXPECT_TRUE(gasp::sameParams(gasp::readParamsYaml(defaults.output, program), gasp::SlamParams{})) << program;
    // A file's values are the effective ones, and what is printed loads back to them.
    const auto printed = runProgram(program, "--params " + file + " --print-params", "/dev/null");
    ASSERT_EQ(printed.exit_code, 0) << program << ": " << printed.output;
    const gasp::SlamParams p = gasp::readParamsYaml(printed.output, program + " --print-params");
    EXPECT_TRUE(gasp::sameParams(p, changed())) << program << "\n" << printed.output;
    const std::string again_path = write(dir + "/" + program + ".yaml", printed.output);
    const auto again = runProgram(program, "--params=" + again_path + " --print-params", "/dev/null");
    ASSERT_EQ(again.exit_code, 0) << program;
    EXPECT_EQ(again.output, printed.output) << program;
  }
}

TEST(ParamsPrograms, AProgramsOwnOptionsOverrideTheFile) {
  const std::string dir = gasp::test::scratchDir();
  const std::string file = write(dir + "/changed.yaml", kChanged);
  auto printed = [&](const std::string& program, const std::string& options) {
    const auto run = runProgram(program, "--params " + file + " " + options + " --print-params", "/dev/null");
    EXPECT_EQ(run.exit_code, 0) << program << " " << options << ": " << run.output;
    return gasp::readParamsYaml(run.output, program);
  };
  EXPECT_DOUBLE_EQ(printed("gasp-segment", "--area-cm2 70").odometry.pair.segment.target_patch_area_m2, 0.007);
  const gasp::SlamParams no_refine = printed("gasp-associate", "--no-refine");
  EXPECT_FALSE(no_refine.odometry.pair.hypothesise.pose.refine);
  EXPECT_EQ(no_refine.odometry.pair.refine.dense.rounds, 0);
  EXPECT_EQ(no_refine.odometry.pair.associate.lambda, 0.65);
  EXPECT_EQ(printed("gasp-odometry", "--keyframe-angle 12").odometry.keyframe_angle_deg, 12.0);
  EXPECT_EQ(printed("gasp-odometry", "").odometry.keyframe_angle_deg, 7.5);
  EXPECT_FALSE(printed("gasp-slam", "--no-loop-closures").loop.enabled);
  EXPECT_EQ(printed("gasp-slam", "--rolling-shutter 0.03").odometry.rolling_shutter_readout_s, 0.03);
  // gasp-graphslam: an --ini's keys over the file's, in the deciders' sections.
  const std::string ini = write(dir + "/over.ini", "[CGaspOdometryNRD]\nkeyframe_angle_deg = 9\n"
                                                   "[CGaspLoopClosureERD]\ngate_chi2 = 15\n");
  const gasp::SlamParams graphslam = printed("gasp-graphslam", "--ini " + ini);
  EXPECT_EQ(graphslam.odometry.keyframe_angle_deg, 9.0);
  EXPECT_EQ(graphslam.loop.gate_chi2, 15.0);
  EXPECT_EQ(graphslam.loop.min_inliers, 25);
  EXPECT_EQ(graphslam.odometry.pair.associate.lambda, 0.65);
  EXPECT_EQ(graphslam.graph.function_tolerance, 1e-12);
}

TEST(ParamsPrograms, ABadParamsFileIsAnErrorNamingTheFileLineAndKey) {
  const std::string dir = gasp::test::scratchDir();
  const std::string bad = write(dir + "/bad.yaml", "associate:\n  lambda: 0.5\n  candiates: 3\n");
  for (const std::string program : kPrograms) {
    const auto run = runProgram(program, "--params " + bad + " --print-params");
    EXPECT_EQ(run.exit_code, 1) << program;
    EXPECT_TRUE(contains(run.output, "error: params '" + bad + "' line 3: unknown key 'candiates' in section 'associate'"))
        << program << ": " << run.output;
  }
  const auto missing = runProgram("gasp-pairs", "--params " + dir + "/none.yaml --tum " + dir);
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_TRUE(contains(missing.output, "error: params '" + dir + "/none.yaml': cannot open the file")) << missing.output;
}
