// gasp-loops end to end: loop detection without odometry on a simulated folder (exact truth),
// its CSVs, and bad input.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "gasp_test_data.h"
#include "program_run.h"

namespace {

using gasp::test::contains;
using gasp::test::countLinesStartingWith;
using gasp::test::runProgram;

std::size_t printedCount(const std::string& output, const std::string& key) {
  const auto pos = output.find(key);
  return pos == std::string::npos ? static_cast<std::size_t>(-1) : std::stoul(output.substr(pos + key.size()));
}

}  // namespace

TEST(GaspLoopsProgram, DetectsTheSimulatedRoomsRevisitsWithNoWrongPose) {
  const std::string out = gasp::test::scratchDir();
  auto run = runProgram("gasp-simulate", "--out " + out + "/sim --frames 30 --rate 5");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  run = runProgram("gasp-loops", "--tum " + out + "/sim --every 2 --min-gap 3 --csv " + out + "/d.csv --curve-csv " + out +
                                     "/pr.csv");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_TRUE(contains(run.output, "keyframes: 15 ")) << run.output;
  EXPECT_EQ(printedCount(run.output, "queries: "), 12u) << run.output;
  const std::size_t registrations = printedCount(run.output, "registrations: ");
  ASSERT_GT(registrations, 0u) << run.output;
  EXPECT_LE(registrations, 36u);  // 3 candidates per query at most
  // The exact truth: every detection within 5 cm and 2 deg; some at the loop closer's threshold.
  const std::size_t detections = printedCount(run.output, "detections: ");
  EXPECT_GT(detections, 4u) << run.output;
  EXPECT_TRUE(contains(run.output, "detections: " + std::to_string(detections) + " (" + std::to_string(detections) +
                                       " within 5 cm and 2 deg"))
      << run.output;
  EXPECT_TRUE(contains(run.output, "within_5cm_2deg: at >= 40 inliers precision 1.000")) << run.output;
  EXPECT_EQ(countLinesStartingWith(out + "/d.csv", "query_frame,"), 1u);
  std::ifstream csv(out + "/d.csv");
  std::size_t lines = 0;
  for (std::string line; std::getline(csv, line);) ++lines;
  EXPECT_EQ(lines, registrations + 1);
  EXPECT_GE(countLinesStartingWith(out + "/pr.csv", "within_5cm_2deg,"), 1u);
  EXPECT_GE(countLinesStartingWith(out + "/pr.csv", "consistent,"), 1u);
}

TEST(GaspLoopsProgram, BadInputExitsWith1OrAUsageCode) {
  const std::string out = gasp::test::scratchDir();
  auto run = runProgram("gasp-loops", "--tum " + out + "/nothing");
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_TRUE(contains(run.output, "nothing")) << run.output;
  run = runProgram("gasp-loops", "");
  EXPECT_EQ(run.exit_code, 2) << run.output;
  run = runProgram("gasp-loops", "--tum " + out + " --candidates 0");
  EXPECT_EQ(run.exit_code, 2) << run.output;
  // A folder without a reference: nothing to score against.
  run = runProgram("gasp-simulate", "--out " + out + "/sim --frames 8 --rate 5");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  std::remove((out + "/sim/groundtruth.txt").c_str());
  run = runProgram("gasp-loops", "--tum " + out + "/sim");
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_TRUE(contains(run.output, "no reference")) << run.output;
}
