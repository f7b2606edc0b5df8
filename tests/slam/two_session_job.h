#pragma once
// Test helper: a small map-building job of two sessions for gasp-slam's job-level tests
// (checkpoint and resume, MPI): a 45-frame simulated room at 10 Hz cut into frames 0-24 and
// 20-44 (they share frames 20-24: relocalisation joins them), the loop searches in place
// (loop_closure.background: false), so that the job's outputs are a function of its inputs.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "program_run.h"

namespace gasp::test {

struct TwoSessionJob {
  std::string dir;
  /// gasp-slam's arguments writing DIR/NAME.session1.txt, .session2.txt and DIR/NAME.graph.
  std::string args(const std::string& name) const {
    return "--session " + dir + "/room@0-24 --session " + dir + "/room@20-44 --params " + dir + "/inplace.yaml --out " +
           dir + "/" + name + ".txt --graph " + dir + "/" + name + ".graph";
  }
};

/// The job's inputs made in `dir` (a scratch folder); a failed simulation fails the test.
inline TwoSessionJob twoSessionJob(const std::string& dir) {
  const auto run = runProgram("gasp-simulate", "--out " + dir + "/room --frames 45 --rate 10");
  EXPECT_EQ(run.exit_code, 0) << run.output;
  std::ofstream(dir + "/inplace.yaml") << "loop_closure:\n  background: false\n";
  return {dir};
}

}  // namespace gasp::test
