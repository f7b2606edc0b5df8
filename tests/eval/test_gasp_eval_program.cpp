// End-to-end checks of the gasp-eval program: output lines and exit codes.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>
#include <memory>

#include "gasp/core/tum_trajectory.h"
#include "gasp_test_data.h"
#include "program_run.h"

namespace {

gasp::test::ProgramRun run(const std::string& args) { return gasp::test::runProgram("gasp-eval", args); }

void writeLine(const std::string& path, int n, double dx) {
  gasp::Trajectory t;
  for (int i = 0; i < n; ++i)
    t.push_back({1.0 + i / 30.0, gasp::Isometry3(Eigen::Translation3d(i * dx, 0.1 * (i % 3), 0))});
  gasp::writeTumTrajectory(path, t);
}

}  // namespace

TEST(GaspEvalProgram, AteAndRpePrintTumStyleLines) {
  const std::string dir = gasp::test::scratchDir();
  writeLine(dir + "/gt.txt", 30, 0.05);
  writeLine(dir + "/est.txt", 30, 0.05);
  auto r = run("ate --gt " + dir + "/gt.txt --est " + dir + "/est.txt --aligned " + dir + "/al.txt");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("compared_pose_pairs: 30"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("absolute_translational_error.rmse: 0.000000 m"), std::string::npos) << r.output;
  EXPECT_EQ(gasp::readTumTrajectory(dir + "/al.txt").size(), 30u);
  r = run("rpe --gt " + dir + "/gt.txt --est " + dir + "/est.txt --delta 2 --delta-unit frames");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("compared_pose_pairs: 27"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("rotational_error.median:"), std::string::npos) << r.output;
}

TEST(GaspEvalProgram, BadInputExitsNonZeroWithMessage) {
  const std::string dir = gasp::test::scratchDir();
  writeLine(dir + "/gt.txt", 10, 0.05);
  std::ofstream(dir + "/bad.txt") << "1.0 0 0 0 0 0 0 1\n2.0 0 0 x 0 0 0 1\n";
  auto r = run("ate --gt " + dir + "/gt.txt --est " + dir + "/bad.txt");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.output.find("bad.txt:2"), std::string::npos) << r.output;
  r = run("ate --gt " + dir + "/gt.txt --est " + dir + "/missing.txt");
  EXPECT_NE(r.exit_code, 0);
  r = run("rpe --gt " + dir + "/gt.txt --est " + dir + "/gt.txt --delta-unit parsecs");
  EXPECT_NE(r.exit_code, 0);
  r = run("");
  EXPECT_EQ(r.exit_code, 2);  // usage errors are 2, whatever CLI11's own code
  // Non-finite or non-positive option values are usage errors, never a NaN printed with exit 0.
  for (const char* option : {"--scale nan", "--scale inf", "--scale 0", "--scale -1", "--max-dt nan", "--max-dt -1",
                             "--offset nan"}) {
    r = run("ate --gt " + dir + "/gt.txt --est " + dir + "/gt.txt " + option);
    EXPECT_EQ(r.exit_code, 2) << option << '\n' << r.output;
    r = run("rpe --gt " + dir + "/gt.txt --est " + dir + "/gt.txt " + option);
    EXPECT_EQ(r.exit_code, 2) << option << '\n' << r.output;
  }
  // A position beyond 1e8 m loses its centimetres in double precision: refused, naming the line.
  std::ofstream(dir + "/huge.txt") << "1.0 0 0 0 0 0 0 1\n2.0 1e300 0 0 0 0 0 1\n";
  r = run("rpe --gt " + dir + "/gt.txt --est " + dir + "/huge.txt");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.output.find("huge.txt:2: translation"), std::string::npos) << r.output;
  // A scale whose products overflow, and a delta that pairs each pose with itself: errors.
  r = run("ate --gt " + dir + "/gt.txt --est " + dir + "/gt.txt --scale 1e160");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_EQ(r.output.find("nan"), std::string::npos) << r.output;
  r = run("rpe --gt " + dir + "/gt.txt --est " + dir + "/gt.txt --delta 1e-300");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("below the poses' spacing"), std::string::npos) << r.output;
  // --aligned onto an input would destroy it before it is read again: refused before the work.
  writeLine(dir + "/keep.txt", 10, 0.05);
  std::ifstream before_in(dir + "/keep.txt");
  const std::string before((std::istreambuf_iterator<char>(before_in)), std::istreambuf_iterator<char>());
  r = run("ate --gt " + dir + "/gt.txt --est " + dir + "/keep.txt --aligned " + dir + "/./keep.txt");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("is an input of this run"), std::string::npos) << r.output;
  std::ifstream after_in(dir + "/keep.txt");
  const std::string after((std::istreambuf_iterator<char>(after_in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(before, after);
}
