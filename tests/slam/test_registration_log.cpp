// RegistrationLog (registration_log.h): a map-building run cut short and resumed from its journal
// builds the uninterrupted run's graph without registering again what it had registered.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "gasp/core/error.h"
#include "gasp/slam/depth_slam.h"
#include "gasp/slam/registration_log.h"
#include "gasp_test_data.h"
#include "loop_sequence.h"

namespace {

using gasp::test::circleSequence;
using gasp::test::LoopSequence;

/// The circle with its searches in place, through `log`'s registrar.
std::unique_ptr<gasp::DepthSlam> run(const LoopSequence& s, const gasp::RegistrationLog& log) {
  gasp::SlamParams p;
  p.loop.background = false;
  auto slam = std::make_unique<gasp::DepthSlam>(p, s.T_world_camera[0]);
  slam->setRegistrar(log.registrar());
  for (std::size_t i = 0; i < s.depth.size(); ++i) slam->addFrame(s.timestamps[i], s.depth[i], s.K);
  slam->finishLoops();
  return slam;
}

void writeText(const std::string& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

/// The first `lines` lines of `text`.
std::string firstLines(const std::string& text, std::size_t lines) {
  std::size_t at = 0;
  for (std::size_t i = 0; i < lines; ++i) at = text.find('\n', at) + 1;
  return text.substr(0, at);
}

/// `journal` without each record's registration time (field 11: a wall-clock time, which a
/// registration made again does not repeat).
std::string withoutTimes(const std::string& journal) {
  std::string out;
  std::size_t at = 0;
  while (at < journal.size()) {
    const std::size_t end = journal.find('\n', at);
    std::string line = journal.substr(at, end - at);
    std::size_t field = 0, start = 0;
    for (std::size_t i = 0; i < 10 && start != std::string::npos; ++i) start = line.find('\t', start) + 1;
    if (line.rfind("R\t", 0) == 0 && start != 0) {
      field = line.find('\t', start);
      line.erase(start, field - start);
    }
    out += line + "\n";
    at = end == std::string::npos ? journal.size() : end + 1;
  }
  return out;
}

std::string tempPath(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("gasp_registration_log_" + std::to_string(::getpid()) + "_" + name))
      .string();
}

}  // namespace

TEST(RegistrationLog, ARunResumedFromHalfItsJournalBuildsTheSameGraphRegisteringOnlyTheRest) {
  const LoopSequence s = circleSequence(30, {12, 13, 14});  // near loops and relocalisation
  const std::string job = "the circle, in-place searches";
  const std::string full_path = tempPath("full.txt"), cut_path = tempPath("cut.txt");

  gasp::RegistrationLog full(job);
  full.journalTo(full_path);
  const auto uninterrupted = run(s, full);
  const std::size_t n = full.registered();
  ASSERT_GE(n, 4u);
  EXPECT_EQ(full.answered(), 0u);
  EXPECT_EQ(uninterrupted->attempts().size(), n);

  // Killed after half the registrations, in the middle of writing the next one.
  const std::string journal = gasp::test::fileText(full_path);
  const std::string next = firstLines(journal, 2 + n / 2).substr(firstLines(journal, 1 + n / 2).size());
  writeText(cut_path, firstLines(journal, 1 + n / 2) + next.substr(0, next.size() / 2));
  gasp::RegistrationLog resumed = gasp::RegistrationLog::read(cut_path, job);
  EXPECT_EQ(resumed.size(), n / 2);  // the torn line dropped
  resumed.journalTo(cut_path);       // and cut off
  const auto again = run(s, resumed);
  EXPECT_EQ(resumed.answered(), n / 2);
  EXPECT_EQ(resumed.registered(), n - n / 2);
  EXPECT_EQ(resumed.size(), n);

  // The same graph: attempts, closures, poses (the same arithmetic in the same order).
  ASSERT_EQ(again->attempts().size(), uninterrupted->attempts().size());
  for (std::size_t i = 0; i < n; ++i) {
    const auto &a = uninterrupted->attempts()[i], &b = again->attempts()[i];
    EXPECT_EQ(a.from, b.from) << i;
    EXPECT_EQ(a.to, b.to) << i;
    EXPECT_EQ(a.accepted, b.accepted) << i;
    EXPECT_EQ(a.inliers, b.inliers) << i;
    EXPECT_EQ(a.reason, b.reason) << i;
  }
  ASSERT_EQ(again->loopClosures().size(), uninterrupted->loopClosures().size());
  ASSERT_FALSE(again->loopClosures().empty());
  for (std::size_t i = 0; i < again->loopClosures().size(); ++i) {
    EXPECT_EQ(again->loopClosures()[i].from, uninterrupted->loopClosures()[i].from);
    EXPECT_EQ(again->loopClosures()[i].to, uninterrupted->loopClosures()[i].to);
    EXPECT_TRUE(again->loopClosures()[i].T_from_to.isApprox(uninterrupted->loopClosures()[i].T_from_to, 0.0));
    EXPECT_TRUE(again->loopClosures()[i].information == uninterrupted->loopClosures()[i].information);
  }
  ASSERT_EQ(again->poses().size(), uninterrupted->poses().size());
  for (std::size_t i = 0; i < again->poses().size(); ++i)
    EXPECT_TRUE(again->poses()[i].matrix() == uninterrupted->poses()[i].matrix()) << "frame " << i;

  // The continued journal holds every registration, in the order made (their times aside): a
  // replay registers none.
  EXPECT_EQ(withoutTimes(gasp::test::fileText(cut_path)), withoutTimes(journal));
  const gasp::RegistrationLog replay = gasp::RegistrationLog::read(cut_path, job);
  const auto replayed = run(s, replay);
  EXPECT_EQ(replay.registered(), 0u);
  EXPECT_EQ(replay.answered(), n);
  EXPECT_EQ(replayed->poses().back().matrix(), uninterrupted->poses().back().matrix());

  // Another job's journal, another file, a damaged record: errors naming the file.
  try {
    (void)gasp::RegistrationLog::read(full_path, "another job");
    ADD_FAILURE() << "another job's journal was read";
  } catch (const gasp::Error& e) {
    EXPECT_NE(std::string(e.what()).find("another job's"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(full_path), std::string::npos) << e.what();
  }
  writeText(cut_path, "not a journal\n");
  EXPECT_THROW((void)gasp::RegistrationLog::read(cut_path, job), gasp::Error);
  std::string damaged = journal;
  damaged[damaged.find('\n') + 1] = 'X';  // the first record
  writeText(cut_path, damaged);
  try {
    (void)gasp::RegistrationLog::read(cut_path, job);
    ADD_FAILURE() << "a damaged journal was read";
  } catch (const gasp::Error& e) {
    EXPECT_NE(std::string(e.what()).find("line 2"), std::string::npos) << e.what();
  }
  EXPECT_THROW((void)gasp::RegistrationLog::read(tempPath("absent.txt"), job), gasp::Error);
  std::filesystem::remove(full_path);
  std::filesystem::remove(cut_path);
}

TEST(RegistrationLog, AFailureOfTheJobEndsItAndARegistrationThatFailedElsewhereIsNotKept) {
  const LoopSequence s = circleSequence(30);
  gasp::SlamParams p;
  p.loop.background = false;

  // A registrar whose first registration failed where it ran (another process): the search goes
  // on without it, and the journal does not keep it (a resumed job tries it again).
  const std::string path = tempPath("failed.txt");
  gasp::RegistrationLog log("the circle");
  log.journalTo(path);
  bool failed_one = false;
  gasp::DepthSlam slam(p, s.T_world_camera[0]);
  slam.setRegistrar(log.registrar([&](std::size_t k, const gasp::DepthView& view_k,
                                      const std::vector<std::pair<std::size_t, const gasp::DepthView*>>& candidates,
                                      bool relocalisation, const gasp::PairParams& pair, const gasp::LoopClosureParams& loop) {
    auto out = gasp::registerCandidates(k, view_k, candidates, relocalisation, pair, loop);
    if (!failed_one && !out.empty()) {
      failed_one = true;
      out[0].attempt.reason = std::string(gasp::kRegistrationFailed) + " on rank 1: out of memory";
    }
    return out;
  }));
  for (std::size_t i = 0; i < s.depth.size(); ++i) slam.addFrame(s.timestamps[i], s.depth[i], s.K);
  ASSERT_TRUE(failed_one);
  EXPECT_EQ(log.registered(), slam.attempts().size());
  EXPECT_EQ(log.size(), slam.attempts().size() - 1);
  EXPECT_EQ(gasp::RegistrationLog::read(path, "the circle").size(), log.size());
  EXPECT_FALSE(slam.attempts().front().accepted);
  std::filesystem::remove(path);

  // A failure of the job (a journal that cannot be appended, another process gone) is a JobError,
  // which DepthSlam passes on: not a gasp::Error, which a program reading several sessions would
  // take for the session's.
  static_assert(!std::is_base_of_v<gasp::Error, gasp::JobError>);
  gasp::DepthSlam failing(p, s.T_world_camera[0]);
  failing.setRegistrar([](std::size_t, const gasp::DepthView&, const std::vector<std::pair<std::size_t, const gasp::DepthView*>>&,
                          bool, const gasp::PairParams&, const gasp::LoopClosureParams&) -> std::vector<gasp::LoopRegistration> {
    throw gasp::JobError("cannot write registration journal 'j': No space left on device");
  });
  EXPECT_THROW(
      {
        for (std::size_t i = 0; i < s.depth.size(); ++i) failing.addFrame(s.timestamps[i], s.depth[i], s.K);
      },
      gasp::JobError);
}
