// The programs' outputs under faults and hostile paths (issue 44): a failed write is an error,
// never exit 0; no output replaces an input or a non-regular file; a killed or failed run leaves
// nothing behind; outputs are opened before the work; a rawlog that ends early still gives the
// results of the frames before the damage, marked partial. On a simulated sequence (no real data).
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <opencv2/imgcodecs.hpp>
#include <fstream>
#include <string>
#include <vector>

#include "gasp/core/tum_dataset.h"
#include "gasp_test_data.h"
#include "program_run.h"

namespace fs = std::filesystem;

namespace {

using gasp::test::fileText;
using gasp::test::namesIn;

using gasp::test::contains;
using gasp::test::ProgramRun;
using gasp::test::runProgram;

/// A simulated TUM folder of 12 frames at 5 Hz (far enough apart for keyframes) with ground truth, made once for the whole file, and a
/// rawlog of it.
struct Sequence {
  std::string dir;
  std::string tum;
  std::string rawlog;
  std::string first_depth;  ///< the first depth image (an input no output may replace)
};

const Sequence& sequence() {
  static const Sequence s = [] {
    Sequence q;
    // A folder of this process's own (ctest runs each test in a process of its own, in parallel),
    // apart from the tests' scratch folders.
    q.dir = std::string(GASP_TEST_TMP_DIR) + "/OutputSafety.sequence." + std::to_string(::getpid());
    fs::remove_all(q.dir);
    fs::create_directories(q.dir);
    q.tum = q.dir + "/sim";
    const ProgramRun sim = runProgram("gasp-simulate", "--out " + q.tum + " --frames 12 --rate 5 --seed 3");
    if (sim.exit_code != 0) throw std::runtime_error("gasp-simulate failed: " + sim.output);
    q.rawlog = q.dir + "/sim.rawlog";
    const ProgramRun conv = runProgram("gasp-tum2rawlog", q.tum + " " + q.rawlog);
    if (conv.exit_code != 0) throw std::runtime_error("gasp-tum2rawlog failed: " + conv.output);
    q.first_depth = q.tum + "/" + gasp::readTumFileList(q.tum + "/depth.txt").front().second;
    return q;
  }();
  return s;
}

/// The command run by /bin/sh with SIGXFSZ ignored and a file-size limit of `blocks` (ulimit -f):
/// a write past it fails as on a full disk.
ProgramRun runLimited(int blocks, const std::string& program, const std::string& args) {
  return gasp::test::runCommand("trap '' XFSZ; ulimit -f " + std::to_string(blocks) + "; exec " +
                                 std::string(GASP_BIN_DIR) + "/" + program + " " + args + " 2>&1");
}

}  // namespace

TEST(OutputSafety, AnOutputThatIsNotARegularFileIsRefusedBeforeTheWork) {
  const Sequence& s = sequence();
  const std::string base = "--tum " + s.tum + " --max-frames 4 ";
  const std::string out = "--out " + s.dir + "/t.txt ";
  for (const std::string program : {"gasp-odometry", "gasp-slam"})
    for (const std::string option : {"--out", "--graph", "--frames-csv"}) {
      const ProgramRun r = runProgram(program, base + (option == "--out" ? "" : out) + option + " /dev/full");
      EXPECT_EQ(r.exit_code, 1) << program << ' ' << option << ": " << r.output;
      EXPECT_TRUE(contains(r.output, "'/dev/full': is not a regular file")) << r.output;
      EXPECT_FALSE(contains(r.output, "intrinsics:")) << "the sequence was opened before the outputs: " << r.output;
    }
  for (const std::string option : {"--odometry-out", "--loops-csv", "--marginals-csv", "--simplemap", "--cloud",
                                   "--sessions-report"}) {
    const ProgramRun r = runProgram("gasp-slam", base + out + option + " /dev/full");
    EXPECT_EQ(r.exit_code, 1) << option << ": " << r.output;
    EXPECT_TRUE(contains(r.output, option + " '/dev/full'")) << r.output;
  }
  for (const std::string option : {"--csv", "--curve-csv"}) {
    const ProgramRun r = runProgram("gasp-loops", base + option + " /dev/full");
    EXPECT_EQ(r.exit_code, 1) << option << ": " << r.output;
    EXPECT_TRUE(contains(r.output, option + " '/dev/full'")) << r.output;
    EXPECT_FALSE(contains(r.output, "keyframes:")) << "the sequence was read before the outputs: " << r.output;
  }
  const ProgramRun eval = runProgram("gasp-eval", "ate --gt " + s.tum + "/groundtruth.txt --est " + s.tum +
                                                      "/groundtruth.txt --aligned /dev/full");
  EXPECT_EQ(eval.exit_code, 1) << eval.output;
  for (const std::string option : {"--csv", "--pairs-csv"}) {
    const ProgramRun pairs = runProgram("gasp-pairs", "--tum " + s.tum + " --skips 1 --max-pairs 1 " + option + " /dev/full");
    EXPECT_EQ(pairs.exit_code, 1) << pairs.output;
  }
  // /proc takes no new file: found when the output is opened, before the run.
  const ProgramRun proc = runProgram("gasp-slam", "--tum " + s.tum + " --out /proc/gasp-test.txt");
  EXPECT_EQ(proc.exit_code, 1) << proc.output;
  EXPECT_TRUE(contains(proc.output, "/proc/gasp-test.txt")) << proc.output;
  EXPECT_FALSE(contains(proc.output, "intrinsics:")) << proc.output;
}

TEST(OutputSafety, AWriteThatFailsMidwayIsAnErrorAndLeavesNoCutFile) {
  const Sequence& s = sequence();
  const std::string dir = gasp::test::scratchDir();
  // The trajectory fits in the limit, the point cloud does not.
  const ProgramRun r = runLimited(8, "gasp-slam", "--tum " + s.tum + " --max-frames 4 --out " + dir + "/t.txt --cloud " + dir + "/c.ply");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_TRUE(contains(r.output, "cannot write --cloud '" + dir + "/c.ply': File too large")) << r.output;
  EXPECT_EQ(namesIn(dir), std::vector<std::string>{"t.txt"}) << "a cut or temporary file was left";
  EXPECT_GT(gasp::test::countLinesStartingWith(dir + "/t.txt", "1"), 0u);
  // Three poses fit in one block of 512 bytes, their graph (an information matrix per edge) does not.
  const ProgramRun odo =
      runLimited(1, "gasp-odometry", "--tum " + s.tum + " --max-frames 3 --out " + dir + "/o.txt --graph " + dir + "/o.graph");
  EXPECT_EQ(odo.exit_code, 1) << odo.output;
  EXPECT_TRUE(contains(odo.output, "cannot write --graph '" + dir + "/o.graph': File too large")) << odo.output;
  EXPECT_EQ(namesIn(dir), (std::vector<std::string>{"o.txt", "t.txt"}));
}

TEST(OutputSafety, NoOutputReplacesAnInputImage) {
  const Sequence& s = sequence();
  const std::string copy = gasp::test::scratchDir() + "/copy";
  fs::copy(s.tum, copy, fs::copy_options::recursive);
  const std::string image = copy + "/" + gasp::readTumFileList(copy + "/depth.txt").front().second;
  const std::string before = fileText(image);
  fs::create_hard_link(image, copy + "/hard.png");
  fs::create_symlink(image, copy + "/soft.png");
  for (const std::string& target : {image, copy + "/hard.png", copy + "/soft.png"}) {
    const std::vector<std::pair<std::string, std::string>> runs{
        {"gasp-associate", "--tum " + copy + " --from 0 --to 4 --out " + target},
        {"gasp-odometry", "--tum " + copy + " --out " + target},
        {"gasp-slam", "--tum " + copy + " --out " + copy + "/t.txt --cloud " + target},
        {"gasp-slam", "--session " + copy + "@0-3 --session " + copy + "@4-7 --out " + copy + "/t.txt --sessions-report " + target},
        {"gasp-loops", "--tum " + copy + " --csv " + target},
        {"gasp-tum2rawlog", copy + " " + target},
        {"gasp-segment", "--depth " + image + " --out " + target},
    };
    for (const auto& [program, args] : runs) {
      const ProgramRun r = runProgram(program, args);
      EXPECT_EQ(r.exit_code, 1) << program << ' ' << args << ": " << r.output;
      EXPECT_TRUE(contains(r.output, "is an input of this run")) << program << ": " << r.output;
      ASSERT_EQ(fileText(image), before) << program << " " << args << " changed an input image";
    }
  }
}

TEST(OutputSafety, Tum2RawlogKeepsALinkAndRefusesADevice) {
  const Sequence& s = sequence();
  const std::string dir = gasp::test::scratchDir();
  const ProgramRun device = runProgram("gasp-tum2rawlog", s.tum + " /dev/null");
  EXPECT_EQ(device.exit_code, 1) << device.output;
  EXPECT_TRUE(contains(device.output, "not a regular file")) << device.output;
  struct stat st {};
  ASSERT_EQ(::stat("/dev/null", &st), 0);
  EXPECT_TRUE(S_ISCHR(st.st_mode)) << "/dev/null was replaced";

  fs::create_directories(dir + "/store");
  fs::create_symlink("store/real.rawlog", dir + "/link.rawlog");
  const ProgramRun link = runProgram("gasp-tum2rawlog", s.tum + " " + dir + "/link.rawlog --max-frames 3");
  EXPECT_EQ(link.exit_code, 0) << link.output;
  EXPECT_TRUE(fs::is_symlink(dir + "/link.rawlog"));
  EXPECT_GT(fs::file_size(dir + "/store/real.rawlog"), 0u);
  // Nothing but the outputs: no temporary or partial file.
  EXPECT_EQ(namesIn(dir), (std::vector<std::string>{"link.rawlog", "link_groundtruth.txt", "store"}));
  EXPECT_EQ(namesIn(dir + "/store"), std::vector<std::string>{"real.rawlog"});
}

TEST(OutputSafety, ATruncatedRawlogGivesThePartialResultsAndAnError) {
  const Sequence& s = sequence();
  const std::string dir = gasp::test::scratchDir();
  const std::string bytes = fileText(s.rawlog);
  const std::string cut = dir + "/cut.rawlog";
  std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() * 9 / 10);
  const std::string gt = " --gt " + s.rawlog.substr(0, s.rawlog.size() - 7) + "_groundtruth.txt";
  for (const std::string program : {"gasp-odometry", "gasp-slam"}) {
    const std::string out = dir + "/" + program + ".txt";
    const ProgramRun r = runProgram(program, "--rawlog " + cut + gt + " --out " + out + " --frames-csv " + out + ".csv");
    EXPECT_EQ(r.exit_code, 1) << program << ": " << r.output;
    EXPECT_TRUE(contains(r.output, "partial: ")) << r.output;
    EXPECT_TRUE(contains(r.output, "error: rawlog '" + cut + "'")) << r.output;
    ASSERT_TRUE(fs::exists(out)) << program << " wrote nothing";
    EXPECT_EQ(gasp::test::countLinesStartingWith(out, "# PARTIAL"), 1u) << fileText(out);
    const std::size_t poses = gasp::test::countLinesStartingWith(out, "1");
    EXPECT_GE(poses, 8u) << fileText(out);
    EXPECT_LT(poses, 12u) << fileText(out);
    EXPECT_TRUE(fs::exists(out + ".csv"));
  }
  const ProgramRun g = runProgram("gasp-graphslam", "--rawlog " + cut + " --out " + dir + "/g.txt");
  EXPECT_EQ(g.exit_code, 1) << g.output;
  EXPECT_TRUE(contains(g.output, "partial: ")) << g.output;
  EXPECT_EQ(gasp::test::countLinesStartingWith(dir + "/g.txt", "# PARTIAL"), 1u) << g.output;
}

TEST(OutputSafety, BadValuesAndFilesGiveClearErrors) {
  const Sequence& s = sequence();
  const std::string dir = gasp::test::scratchDir();
  // Integers beyond what an option holds are refused, not wrapped.
  const ProgramRun big = runProgram("gasp-pairs", "--tum " + s.tum + " --skips 99999999999999999999");
  EXPECT_EQ(big.exit_code, 2) << big.output;
  EXPECT_TRUE(contains(big.output, "too large")) << big.output;
  EXPECT_EQ(runProgram("gasp-odometry", "--tum " + s.tum + " --out " + dir + "/t.txt --max-frames 99999999999999999999").exit_code, 2);
  // A missing --est is bad input (1), not a usage error.
  const ProgramRun missing = runProgram("gasp-eval", "ate --gt " + s.tum + "/groundtruth.txt --est " + dir + "/none.txt");
  EXPECT_EQ(missing.exit_code, 1) << missing.output;
  EXPECT_TRUE(contains(missing.output, dir + "/none.txt")) << missing.output;
  // A binary file quoted in an error stays one printable line.
  std::ofstream(dir + "/binary.txt", std::ios::binary) << std::string("1.0 \x1b[2J\x01\xff 2 3\n", 16);
  const ProgramRun binary = runProgram("gasp-eval", "ate --gt " + dir + "/binary.txt --est " + s.tum + "/groundtruth.txt");
  EXPECT_EQ(binary.exit_code, 1) << binary.output;
  for (const char c : binary.output) EXPECT_TRUE(c == '\n' || (c >= 0x20 && c != 0x7f)) << binary.output;
  // Two depth images of different sizes: the error names the file that does not fit.
  const cv::Mat small(240, 320, CV_16UC1, cv::Scalar(5000));
  ASSERT_TRUE(cv::imwrite(dir + "/small.png", small));
  const ProgramRun sizes = runProgram("gasp-associate", "--depth-a " + s.first_depth + " --depth-b " + dir + "/small.png --intrinsics " +
                                                            s.tum + "/intrinsics.txt --out " + dir + "/p.png");
  EXPECT_EQ(sizes.exit_code, 1) << sizes.output;
  EXPECT_TRUE(contains(sizes.output, dir + "/small.png")) << sizes.output;
}
