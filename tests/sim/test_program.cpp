// gasp-simulate: exit codes and messages (the logic itself is tested through the library).
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "gasp_test_data.h"

namespace {

struct Run {
  int status = 0;
  std::string output;  // stdout and stderr
};

/// Runs the program with a log file in `dir` (the test's scratch folder).
Run runSimulate(const std::string& args, const std::string& dir) {
  const std::string log = dir + "/log.txt";
  const std::string cmd = std::string(GASP_BIN_DIR) + "/gasp-simulate " + args + " > " + log + " 2>&1";
  Run r;
  r.status = std::system(cmd.c_str());
  std::ifstream in(log);
  r.output.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  return r;
}

}  // namespace

TEST(SimProgram, ListsScenes) {
  const auto r = runSimulate("--list-scenes", gasp::test::scratchDir());
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("room (default)"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("corridor"), std::string::npos) << r.output;
}

TEST(SimProgram, BadInputFailsWithAMessage) {
  const std::string tmp = gasp::test::scratchDir();
  auto r = runSimulate("--scene castle --out " + tmp + "/never", tmp);
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("error: unknown scene 'castle'"), std::string::npos) << r.output;
  r = runSimulate("--frames 3 --out " + tmp + "/never", tmp);
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("--frames: must be between 8 and 20000 (got 3)"), std::string::npos) << r.output;
  r = runSimulate("--frames 8", tmp);
  EXPECT_EQ(WEXITSTATUS(r.status), 2) << r.output;  // a missing option is a usage error, as in every program
  EXPECT_NE(r.output.find("error: --out DIR is required"), std::string::npos) << r.output;
  r = runSimulate("--frames eight --out " + tmp + "/x", tmp);  // CLI11 usage error
  EXPECT_NE(r.status, 0);
  // Rates whose microsecond timestamps would collide, and frame counts beyond the limit, are
  // refused before anything is written; a negative seed does not wrap round.
  r = runSimulate("--rate 1e7 --out " + tmp + "/fast", tmp);
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("--rate: must be between 0.001 and 10000"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(tmp + "/fast/depth.txt"));
  r = runSimulate("--frames 100000 --out " + tmp + "/long", tmp);
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("--frames: must be between 8 and 20000"), std::string::npos) << r.output;
  r = runSimulate("--seed -1 --out " + tmp + "/seed", tmp);
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("--seed: must be at least 0"), std::string::npos) << r.output;
}

TEST(SimProgram, WritesASequenceAndSummary) {
  const std::string tmp = gasp::test::scratchDir();
  const std::string dir = tmp + "/seq";
  const auto r = runSimulate("--scene sparse --frames 8 --seed 5 --no-noise --out " + dir, tmp);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("roll_180"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("valid:"), std::string::npos) << r.output;
  EXPECT_TRUE(std::filesystem::exists(dir + "/depth.txt"));
  EXPECT_TRUE(std::filesystem::exists(dir + "/intrinsics.txt"));
}

TEST(SimProgram, MovesAnObject) {
  const std::string tmp = gasp::test::scratchDir();
  const std::string dir = tmp + "/moved";
  auto r = runSimulate("--frames 8 --no-noise --move chair:0,-0.6,0,30@4 --out " + dir, tmp);
  ASSERT_EQ(r.status, 0) << r.output;
  std::ifstream scene(dir + "/scene.txt"), surfaces(dir + "/surfaces.txt");
  const std::string info((std::istreambuf_iterator<char>(scene)), std::istreambuf_iterator<char>());
  const std::string ids((std::istreambuf_iterator<char>(surfaces)), std::istreambuf_iterator<char>());
  EXPECT_NE(info.find("move: chair:0,-0.6,0,30@4\n"), std::string::npos) << info;
  EXPECT_NE(ids.find("chair_back@moved box"), std::string::npos) << ids;
  r = runSimulate("--frames 8 --move chair:0,-0.6@4 --out " + tmp + "/bad", tmp);
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("error: object move 'chair:0,-0.6@4': expected PREFIX:DX,DY,DZ@FRAME"), std::string::npos)
      << r.output;
  r = runSimulate("--frames 8 --move sofa:0,0,0@4 --out " + tmp + "/bad", tmp);
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("has no object whose name starts with 'sofa'"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(tmp + "/bad/depth.txt"));
}
