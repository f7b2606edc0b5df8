// gasp-slam --mpi (gasp/mpi/registrar_pool.h) under mpirun with 2 and 3 ranks: the same
// trajectories and graph, byte for byte, as the single process, with the sessions tracked and the
// loop registrations made on the other ranks.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "gasp_test_data.h"
#include "program_run.h"
#include "two_session_job.h"

namespace {

using gasp::test::contains;
using gasp::test::fileText;
using gasp::test::printedCount;
using gasp::test::runCommand;
using gasp::test::runProgram;

/// gasp-slam under mpirun with `ranks` processes. As root (a CI container) Open MPI needs both
/// ALLOW variables; --oversubscribe: more ranks than cores; --bind-to none: each rank's threads
/// on every core (with 2 ranks Open MPI would bind each to one); no single-copy shared memory
/// (which containers without ptrace refuse).
/// Skips the test, saying why, when the MPI launcher found at configure time is gone.
#define SKIP_WITHOUT_MPIRUN()                                                                      \
  if (!std::filesystem::exists(GASP_MPIEXEC))                                                      \
  GTEST_SKIP() << "skipped: no " << GASP_MPIEXEC << " (Debian: openmpi-bin)"

gasp::test::ProgramRun mpirun(int ranks, const std::string& args) {
  return runCommand("OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_btl_vader_single_copy_mechanism=none " +
                    std::string(GASP_MPIEXEC) + " --bind-to none --oversubscribe -np " + std::to_string(ranks) + " " +
                    std::string(GASP_BIN_DIR) + "/gasp-slam " + args + " --mpi 2>&1");
}

}  // namespace

TEST(GaspSlamMpi, TwoAndThreeRanksWriteTheSingleProcessGraph) {
  SKIP_WITHOUT_MPIRUN();
  const std::string out = gasp::test::scratchDir();
  const gasp::test::TwoSessionJob two = gasp::test::twoSessionJob(out);
  // With the keyframes' point map: their frames cross from the tracking ranks too. (Not the simple
  // map: its poses' marginal covariances differ in their last bits from run to run, in one process
  // too.)
  const auto job = [&](const std::string& name) {
    return two.args(name) + " --cloud " + out + "/" + name + ".ply --voxel 0.05";
  };
  const auto single = runProgram("gasp-slam", job("single"));
  ASSERT_TRUE(single.exit_code == 0 || single.exit_code == 3) << single.output;
  const std::size_t tried = printedCount(single.output, "loop_closures: ");
  ASSERT_NE(tried, static_cast<std::size_t>(-1)) << single.output;

  for (const int ranks : {2, 3}) {
    const std::string name = "ranks" + std::to_string(ranks);
    const auto mpi = mpirun(ranks, job(name) + (ranks == 2 ? " --checkpoint " + out + "/half.journal" : ""));
    EXPECT_EQ(mpi.exit_code, single.exit_code) << mpi.output;
    EXPECT_TRUE(contains(mpi.output, "mpi: " + std::to_string(ranks) + " ranks: the sessions tracked on rank" +
                                         (ranks == 2 ? " 1," : "s 1-2,")))
        << mpi.output;
    // "mpi: N pairs registered on the other ranks and M on rank 0 while none was free": which rank
    // registers a pair depends on timing, not the pairs.
    const auto at = mpi.output.find(" pairs registered on the other ranks and ");
    ASSERT_NE(at, std::string::npos) << mpi.output;
    const std::size_t line = mpi.output.rfind("mpi: ", at);
    const std::size_t elsewhere = std::stoul(mpi.output.substr(line + 5, at - line - 5));
    const std::size_t here = std::stoul(mpi.output.substr(at + 41));
    EXPECT_GE(elsewhere + here, 4u) << mpi.output;
    for (const std::string file : {".session1.txt", ".session2.txt", ".graph", ".ply"}) {
      const std::string a = fileText(out + "/single" + file), b = fileText(out + "/" + name + file);
      EXPECT_FALSE(a.empty()) << file;
      EXPECT_EQ(a, b) << name << file;
    }
  }

  // With a checkpoint: the 2-rank job's journal cut to half its registrations, resumed on 2 ranks:
  // the journal answers first, rank 1 registers the rest, the outputs are the single process's.
  const std::string journal = fileText(out + "/half.journal");
  std::size_t lines = 0, at = 0;
  for (std::size_t p = journal.find('\n'); p != std::string::npos; p = journal.find('\n', p + 1)) ++lines;
  const std::size_t kept = (lines - 1) / 2;
  for (std::size_t i = 0; i < 1 + kept; ++i) at = journal.find('\n', at) + 1;
  std::ofstream(out + "/half.journal", std::ios::binary | std::ios::trunc) << journal.substr(0, at);
  const auto resumed = mpirun(2, job("resumed") + " --checkpoint " + out + "/half.journal --resume");
  EXPECT_EQ(resumed.exit_code, single.exit_code) << resumed.output;
  EXPECT_TRUE(contains(resumed.output, std::to_string(lines - 1 - kept) + " registrations made, " +
                                           std::to_string(kept) + " answered from it)"))
      << resumed.output;
  for (const std::string file : {".session1.txt", ".session2.txt", ".graph"})
    EXPECT_EQ(fileText(out + "/single" + file), fileText(out + "/resumed" + file)) << file;
}

TEST(GaspSlamMpi, ASessionEndingInAnErrorOnItsRankEndsAsInOneProcess) {
  SKIP_WITHOUT_MPIRUN();
  // The room's frame 29 is a cut PNG: the first session's rank tracks its 9 frames before it and
  // hands the error over; the second session goes on. The outputs (marked partial) and the exit code are
  // the single process's.
  const std::string out = gasp::test::scratchDir();
  const gasp::test::TwoSessionJob two = gasp::test::twoSessionJob(out);
  ASSERT_EQ(std::system(("cp -r " + out + "/room " + out + "/cut").c_str()), 0);
  std::string cut;
  {
    std::ifstream list(out + "/cut/depth.txt");
    std::string line;
    for (int frame = -1; std::getline(list, line);)
      if (!line.empty() && line[0] != '#' && ++frame == 29) cut = out + "/cut/" + line.substr(line.find(' ') + 1);
  }
  ASSERT_FALSE(cut.empty());
  std::ofstream(cut, std::ios::binary | std::ios::trunc) << fileText(cut).substr(0, 100);
  const auto job = [&](const std::string& name) {
    return "--session " + out + "/cut@20-35 --session " + out + "/room@20-30 --params " + out + "/inplace.yaml --out " +
           out + "/" + name + ".txt --graph " + out + "/" + name + ".graph";
  };
  const auto single = runProgram("gasp-slam", job("single"));
  ASSERT_EQ(single.exit_code, 1) << single.output;
  ASSERT_TRUE(contains(single.output, "9 of 9 tracked (PARTIAL")) << single.output;
  const auto mpi = mpirun(3, job("ranks3"));
  EXPECT_EQ(mpi.exit_code, 1) << mpi.output;
  EXPECT_TRUE(contains(mpi.output, "9 of 9 tracked (PARTIAL")) << mpi.output;
  EXPECT_TRUE(contains(mpi.output, "is not a readable image")) << mpi.output;
  for (const std::string file : {".session1.txt", ".session2.txt", ".graph"}) {
    const std::string a = fileText(out + "/single" + file);
    EXPECT_FALSE(a.empty()) << file;
    EXPECT_EQ(a, fileText(out + "/ranks3" + file)) << file;
  }
}

TEST(GaspSlamMpi, LidarSessionsOverThreeRanksWriteTheSingleProcessGraph) {
  // Sweeps cross between the ranks as views with their returns and, for the point map, as frames
  // with their scans: two sessions of a simulated 16-laser sweep sequence, tracked on ranks 1
  // and 2, give the single process's trajectories, graph and point map.
  SKIP_WITHOUT_MPIRUN();
  const std::string out = gasp::test::scratchDir();
  const auto sim = runProgram("gasp-simulate", "--sensor lidar16 --frames 36 --rate 10 --out " + out + "/lidar");
  ASSERT_EQ(sim.exit_code, 0) << sim.output;
  std::ofstream(out + "/inplace.yaml") << "loop_closure:\n  background: false\n";
  const auto job = [&](const std::string& name) {
    const std::string rawlog = out + "/lidar/lidar.rawlog";
    return "--session " + rawlog + "@0-20 --session " + rawlog + "@15-35 --params " + out + "/inplace.yaml --out " +
           out + "/" + name + ".txt --graph " + out + "/" + name + ".graph --cloud " + out + "/" + name +
           ".ply --voxel 0.1";
  };
  const auto single = runProgram("gasp-slam", job("single"));
  ASSERT_TRUE(single.exit_code == 0 || single.exit_code == 3) << single.output;
  const auto mpi = mpirun(3, job("ranks3"));
  EXPECT_EQ(mpi.exit_code, single.exit_code) << mpi.output;
  EXPECT_TRUE(contains(mpi.output, "the sessions tracked on ranks 1-2,")) << mpi.output;
  for (const std::string file : {".session1.txt", ".session2.txt", ".graph", ".ply"}) {
    const std::string a = fileText(out + "/single" + file);
    EXPECT_FALSE(a.empty()) << file;
    EXPECT_EQ(a, fileText(out + "/ranks3" + file)) << file;
  }
}
