// The control of the dense rounds (gasp/pipeline/dense_rounds.h) on scripted steps: poses are
// translations along x, each solve moves the pose by a scripted amount, and the line search's
// score is a scripted function of x. So every path of the control is driven on purpose,
// including the two a review mended without a test: a refused step right after an
// extrapolation jump, and an extrapolation after a shortened step.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "gasp/core/error.h"
#include "gasp/pipeline/dense_rounds.h"

using namespace gasp;

namespace {

Isometry3 atX(double x) {
  Isometry3 T = Isometry3::Identity();
  T.translation().x() = x;
  return T;
}

double xOf(const Isometry3& T) { return T.translation().x(); }

/// Scripted rounds: solve call k (evaluations not counted) moves the pose by step(k); an
/// evaluation returns its start. Records where each solve and each gather started.
struct Script {
  std::function<double(int call)> step;
  std::function<double(double x)> score = [](double) { return 0.0; };
  bool evaluation_fails = false;
  int failing_call = -1;  ///< this solve call fails ("degenerate")

  std::vector<double> solve_starts;                 // plain solves
  std::vector<double> evaluation_starts;            // evaluate-only solves
  std::vector<std::pair<double, int>> gathers;      // (x, round)

  DenseRoundsOps ops() {
    DenseRoundsOps o;
    o.gather = [this](const Isometry3& T, int round) {
      gathers.emplace_back(xOf(T), round);
      GatedTerms g;
      g.terms.resize(10);  // the count only: the scripted solve and score ignore them
      return g;
    };
    o.solve = [this](const Isometry3& start, const std::vector<PointToPlane>&, bool evaluate_only) {
      RegistrationResult r;
      r.success = true;
      if (evaluate_only) {
        evaluation_starts.push_back(xOf(start));
        r.success = !evaluation_fails;
        r.T_target_source = start;
        if (!r.success) r.reason = "evaluation failed";
        return r;
      }
      const int call = static_cast<int>(solve_starts.size());
      solve_starts.push_back(xOf(start));
      if (call == failing_call) {
        r.success = false;
        r.reason = "degenerate";
        return r;
      }
      r.T_target_source = atX(xOf(start) + step(call));
      return r;
    };
    o.score = [this](const GatedTerms&, const Isometry3& T) { return score(xOf(T)); };
    return o;
  }
};

/// Steps by call index; beyond the list, no motion.
std::function<double(int)> steps(std::vector<double> list) {
  return [list = std::move(list)](int call) { return call < static_cast<int>(list.size()) ? list[call] : 0.0; };
}

const std::vector<Eigen::Vector3d> kPoints{{0, 0, 1}, {1, 0, 1}, {0, 1, 2}};  // a translation moves each by itself

/// Two gates (the last from round 1), 2 rounds always, up to 16.
DenseRoundsSettings twoGates() {
  DenseRoundsSettings s;
  s.gates_m = {0.10, 0.03};
  s.rounds = 2;
  s.max_rounds = 16;
  s.converged_m = 0.002;
  s.extrapolation_max = 4.0;
  s.line_search = true;
  s.line_search_halvings = 3;
  return s;
}

RegistrationResult startAt(double x) {
  RegistrationResult r;
  r.success = true;
  r.T_target_source = atX(x);
  return r;
}

constexpr double kTol = 1e-12;

}  // namespace

TEST(DenseRoundControl, AGeometricCreepIsExtrapolatedToItsLimit) {
  // Each solve goes half the way to x = 0.1: steps 0.05, 0.025, 0.0125 agree and shrink by 1/2,
  // so the rest of the series is one more step (s = r / (1 - r) = 1) and the jump lands on 0.1.
  const double limit = 0.1;
  std::vector<double> starts;
  DenseRoundsOps ops;
  ops.gather = [](const Isometry3&, int) { return GatedTerms{}; };
  ops.solve = [&](const Isometry3& start, const std::vector<PointToPlane>&, bool) {
    starts.push_back(xOf(start));
    RegistrationResult r;
    r.success = true;
    r.T_target_source = atX(xOf(start) + 0.5 * (limit - xOf(start)));
    return r;
  };
  DenseRounds rounds;
  const RegistrationResult pose = runDenseRounds(startAt(0.0), kPoints, twoGates(), ops, rounds);
  ASSERT_TRUE(pose.success);
  EXPECT_NEAR(xOf(pose.T_target_source), limit, 1e-9);
  EXPECT_EQ(rounds.run, 4);
  ASSERT_EQ(starts.size(), 4u);
  EXPECT_NEAR(starts[3], limit, 1e-9);  // the fourth round starts at the jump
  EXPECT_LT(rounds.last_step_m, 0.002);

  // Without the extrapolation the same series crawls: 6 rounds, and it stops 1.6 mm short.
  DenseRoundsSettings off = twoGates();
  off.extrapolation_max = 0.0;
  starts.clear();
  const RegistrationResult crawl = runDenseRounds(startAt(0.0), kPoints, off, ops, rounds);
  EXPECT_EQ(rounds.run, 6);
  EXPECT_NEAR(xOf(crawl.T_target_source), limit - 0.1 / 64.0, 1e-9);
}

TEST(DenseRoundControl, ARefusedStepRightAfterAJumpEndsAtTheLastRefinedPoseNotAtTheJump) {
  // Steps 0.08, 0.04, 0.02 (x = 0.14), then a jump of one step to 0.16; the round from there
  // wants +0.05, and every length of that step scores worse than 0.16 (the score peaks at 0.14).
  Script script;
  script.step = steps({0.08, 0.04, 0.02, 0.05});
  script.score = [](double x) { return -std::abs(x - 0.14); };
  DenseRounds rounds;
  const RegistrationResult pose = runDenseRounds(startAt(0.0), kPoints, twoGates(), script.ops(), rounds);
  ASSERT_TRUE(pose.success);
  ASSERT_EQ(script.solve_starts.size(), 4u);
  EXPECT_NEAR(script.solve_starts[3], 0.16, kTol);  // the jump happened
  EXPECT_TRUE(rounds.line_search_stopped);
  EXPECT_EQ(rounds.last_step_m, 0.0);
  EXPECT_EQ(rounds.run, 4);
  EXPECT_EQ(rounds.shortened, 0);
  EXPECT_NEAR(xOf(pose.T_target_source), 0.14, kTol);  // the last refined pose, not the jump (0.16)
  // The search tried the full step and three halvings, gathering at each (with the next round's gate).
  ASSERT_GE(script.gathers.size(), 4u);
  const std::vector<double> tried{0.21, 0.185, 0.1725, 0.16625};
  for (std::size_t i = 0; i < tried.size(); ++i) {
    const auto& g = script.gathers[script.gathers.size() - tried.size() + i];
    EXPECT_NEAR(g.first, tried[i], kTol);
    EXPECT_EQ(g.second, 4);
  }
  EXPECT_TRUE(script.evaluation_starts.empty());
}

TEST(DenseRoundControl, AShortenedStepSeedsNoExtrapolationAndItsTermsAreTheNextRounds) {
  // Steps 0.08, 0.04 (x = 0.12); then +0.06 grows, scores worse at 0.18 than at 0.12 and better
  // at half (0.15): the step is shortened to 0.03. Had the shortened step seeded an
  // extrapolation, the round after it (+0.015, ratio 1/2 to it) would have jumped by +0.015.
  Script script;
  script.step = steps({0.08, 0.04, 0.06, 0.015});
  script.score = [](double x) { return -std::abs(x - 0.145); };
  DenseRounds rounds;
  const RegistrationResult pose = runDenseRounds(startAt(0.0), kPoints, twoGates(), script.ops(), rounds);
  ASSERT_TRUE(pose.success);
  EXPECT_EQ(rounds.shortened, 1);
  EXPECT_FALSE(rounds.line_search_stopped);
  ASSERT_EQ(script.evaluation_starts.size(), 1u);
  EXPECT_NEAR(script.evaluation_starts[0], 0.15, kTol);  // the shortened pose is evaluated there
  ASSERT_GE(script.solve_starts.size(), 5u);
  EXPECT_NEAR(script.solve_starts[3], 0.15, kTol);   // no jump right after the shortened step
  EXPECT_NEAR(script.solve_starts[4], 0.165, kTol);  // nor one from it and the next step
  // Round 3 solved on the terms the search gathered at 0.15 (round 3's gate): no second gather there.
  int gathers_at_015 = 0;
  for (const auto& g : script.gathers)
    if (std::abs(g.first - 0.15) < kTol) {
      ++gathers_at_015;
      EXPECT_EQ(g.second, 3);
    }
  EXPECT_EQ(gathers_at_015, 1);
  EXPECT_NEAR(xOf(pose.T_target_source), 0.165, kTol);  // then no motion: converged there
  EXPECT_EQ(rounds.run, 5);
}

TEST(DenseRoundControl, AShortenedStepBelowTheConvergenceStepDoesNotEndTheRounds) {
  // One gate, extrapolation off. Steps 0.01, 0.003, then +0.0035 grows; halved (0.00175, below
  // converged_m = 0.002) it scores better and is kept, but the solve wanted to go further: the
  // rounds go on, and the next round moves 0.1 mm and converges.
  DenseRoundsSettings s = twoGates();
  s.gates_m = {0.03};
  s.rounds = 1;
  s.extrapolation_max = 0.0;
  Script script;
  script.step = steps({0.01, 0.003, 0.0035, 0.0001});
  script.score = [](double x) { return -std::abs(x - 0.0145); };
  DenseRounds rounds;
  const RegistrationResult pose = runDenseRounds(startAt(0.0), kPoints, s, script.ops(), rounds);
  ASSERT_TRUE(pose.success);
  EXPECT_EQ(rounds.shortened, 1);
  EXPECT_EQ(rounds.run, 4);
  EXPECT_NEAR(xOf(pose.T_target_source), 0.01475 + 0.0001, kTol);
  EXPECT_NEAR(rounds.last_step_m, 0.0001, 1e-12);
}

TEST(DenseRoundControl, AnEqualScoreKeepsTheFullStep) {
  // As above with the score peaking half way between 0.12 and 0.18: the full step scores as the
  // pose it leaves, and is taken whole.
  Script script;
  script.step = steps({0.08, 0.04, 0.06});
  script.score = [](double x) { return -std::abs(x - 0.15); };
  DenseRounds rounds;
  const RegistrationResult pose = runDenseRounds(startAt(0.0), kPoints, twoGates(), script.ops(), rounds);
  ASSERT_TRUE(pose.success);
  EXPECT_EQ(rounds.shortened, 0);
  EXPECT_FALSE(rounds.line_search_stopped);
  EXPECT_NEAR(xOf(pose.T_target_source), 0.18, kTol);
  // The terms gathered where the full step landed are round 3's: one gather at 0.18.
  int gathers_at_018 = 0;
  for (const auto& g : script.gathers) gathers_at_018 += std::abs(g.first - 0.18) < kTol ? 1 : 0;
  EXPECT_EQ(gathers_at_018, 1);
  ASSERT_GE(script.solve_starts.size(), 4u);
  EXPECT_NEAR(script.solve_starts[3], 0.18, kTol);
}

TEST(DenseRoundControl, WithNoHalvingsAWorseStepEndsTheRoundsAtOnce) {
  DenseRoundsSettings s = twoGates();
  s.line_search_halvings = 0;
  Script script;
  script.step = steps({0.08, 0.04, 0.06});
  script.score = [](double x) { return -std::abs(x - 0.145); };  // half the step would score better
  DenseRounds rounds;
  const RegistrationResult pose = runDenseRounds(startAt(0.0), kPoints, s, script.ops(), rounds);
  EXPECT_TRUE(rounds.line_search_stopped);
  EXPECT_EQ(rounds.shortened, 0);
  EXPECT_NEAR(xOf(pose.T_target_source), 0.12, kTol);
  EXPECT_TRUE(script.evaluation_starts.empty());
}

TEST(DenseRoundControl, TheLineSearchJudgesOnlyGrowingStepsAtTheLastGateAboveTheConvergenceStep) {
  // Three gates: round 1 (gate 0.05) grows from 2 to 5 cm and the score says it is worse, but it
  // is not at the last gate: taken, with no gather beyond the three rounds'.
  DenseRoundsSettings s = twoGates();
  s.gates_m = {0.10, 0.05, 0.03};
  s.rounds = 3;
  Script early;
  early.step = steps({0.02, 0.05});
  early.score = [](double x) { return -std::abs(x); };
  DenseRounds rounds;
  RegistrationResult pose = runDenseRounds(startAt(0.0), kPoints, s, early.ops(), rounds);
  EXPECT_NEAR(xOf(pose.T_target_source), 0.07, kTol);
  EXPECT_EQ(early.gathers.size(), 3u);
  EXPECT_FALSE(rounds.line_search_stopped);

  // At the last gate, a growing step below converged_m (1.0 then 1.5 mm) is not judged either:
  // it ends the rounds as converged.
  Script small;
  small.step = steps({0.0010, 0.0015});
  small.score = [](double x) { return -std::abs(x); };
  pose = runDenseRounds(startAt(0.0), kPoints, twoGates(), small.ops(), rounds);
  EXPECT_NEAR(xOf(pose.T_target_source), 0.0025, kTol);
  EXPECT_EQ(small.gathers.size(), 2u);
  EXPECT_EQ(rounds.run, 2);
  EXPECT_FALSE(rounds.line_search_stopped);
}

TEST(DenseRoundControl, StepsBeforeTheLastGateAreNotExtrapolated) {
  // Three gates but one compulsory round: rounds 0 and 1 (gates 0.10 and 0.05) move 4 and 2 cm
  // the same way; they are steps of different problems, so round 2 starts where round 1 ended.
  DenseRoundsSettings s = twoGates();
  s.gates_m = {0.10, 0.05, 0.03};
  s.rounds = 1;
  Script script;
  script.step = steps({0.04, 0.02, 0.01});
  DenseRounds rounds;
  runDenseRounds(startAt(0.0), kPoints, s, script.ops(), rounds);
  ASSERT_GE(script.solve_starts.size(), 3u);
  EXPECT_NEAR(script.solve_starts[2], 0.06, kTol);
}

TEST(DenseRoundControl, NoJumpAfterTheLastRound) {
  // The creep of the first test with max_rounds 3: the third step would be extrapolated, but it
  // is the last round's, so the pose returned is the third refined one (0.0875), not the jump (0.1).
  DenseRoundsSettings s = twoGates();
  s.max_rounds = 3;
  Script script;
  script.step = steps({0.05, 0.025, 0.0125});
  DenseRounds rounds;
  const RegistrationResult pose = runDenseRounds(startAt(0.0), kPoints, s, script.ops(), rounds);
  EXPECT_EQ(rounds.run, 3);
  EXPECT_EQ(script.solve_starts.size(), 3u);
  EXPECT_NEAR(xOf(pose.T_target_source), 0.0875, kTol);
}

TEST(DenseRoundControl, InvalidSettingsOrMissingFunctionsThrow) {
  Script script;
  script.step = steps({});
  DenseRounds rounds;
  const auto runWith = [&](const DenseRoundsSettings& s) { runDenseRounds(startAt(0.0), kPoints, s, script.ops(), rounds); };
  DenseRoundsSettings s = twoGates();
  s.gates_m.clear();
  EXPECT_THROW(runWith(s), Error);
  s = twoGates();
  s.gates_m = {0.1, std::nan("")};
  EXPECT_THROW(runWith(s), Error);
  s = twoGates();
  s.line_search_halvings = -1;
  EXPECT_THROW(runWith(s), Error);
  s = twoGates();
  s.converged_m = std::nan("");
  EXPECT_THROW(runWith(s), Error);
  s = twoGates();
  s.max_rounds = -1;
  EXPECT_THROW(runWith(s), Error);
  DenseRoundsOps missing = script.ops();
  missing.solve = nullptr;
  EXPECT_THROW(runDenseRounds(startAt(0.0), kPoints, twoGates(), missing, rounds), Error);
  EXPECT_NO_THROW(runWith(twoGates()));
}

TEST(DenseRoundControl, AFailedEvaluationOfAShortenedStepIsAStop) {
  Script script;
  script.step = steps({0.08, 0.04, 0.06});
  script.score = [](double x) { return -std::abs(x - 0.145); };
  script.evaluation_fails = true;
  DenseRounds rounds;
  const RegistrationResult pose = runDenseRounds(startAt(0.0), kPoints, twoGates(), script.ops(), rounds);
  ASSERT_TRUE(pose.success);
  EXPECT_TRUE(rounds.line_search_stopped);
  EXPECT_EQ(rounds.shortened, 0);
  EXPECT_EQ(rounds.last_step_m, 0.0);
  EXPECT_NEAR(xOf(pose.T_target_source), 0.12, kTol);
}

TEST(DenseRoundControl, WithoutTheLineSearchAGrowingStepIsTaken) {
  DenseRoundsSettings s = twoGates();
  s.line_search = false;
  Script script;
  script.step = steps({0.08, 0.04, 0.06});
  script.score = [](double x) { return -std::abs(x - 0.14); };
  DenseRounds rounds;
  const RegistrationResult pose = runDenseRounds(startAt(0.0), kPoints, s, script.ops(), rounds);
  EXPECT_NEAR(xOf(pose.T_target_source), 0.18, kTol);
  EXPECT_EQ(rounds.shortened, 0);
  EXPECT_FALSE(rounds.line_search_stopped);
}

TEST(DenseRoundControl, AFailedSolveIsNoPoseWithTheReason) {
  Script script;
  script.step = steps({0.08, 0.04});
  script.failing_call = 1;
  DenseRounds rounds;
  const RegistrationResult pose = runDenseRounds(startAt(0.0), kPoints, twoGates(), script.ops(), rounds);
  EXPECT_FALSE(pose.success);
  EXPECT_EQ(pose.reason, "dense refinement: degenerate");
  EXPECT_EQ(rounds.run, 2);
  EXPECT_NEAR(rounds.last_step_m, 0.08, kTol);  // of the last round that succeeded
}

TEST(DenseRoundControl, TheFirstRoundsAlwaysRunAndTheGatesFollowTheRounds) {
  // No motion at all: still `rounds` rounds, each gathered with its own round index.
  DenseRoundsSettings s = twoGates();
  s.rounds = 3;
  Script script;
  script.step = steps({});
  DenseRounds rounds;
  const RegistrationResult pose = runDenseRounds(startAt(0.5), kPoints, s, script.ops(), rounds);
  ASSERT_TRUE(pose.success);
  EXPECT_EQ(rounds.run, 3);
  EXPECT_EQ(rounds.terms, 10);
  ASSERT_EQ(script.gathers.size(), 3u);
  for (int r = 0; r < 3; ++r) EXPECT_EQ(script.gathers[static_cast<std::size_t>(r)].second, r);
  EXPECT_NEAR(xOf(pose.T_target_source), 0.5, kTol);

  // max_rounds bounds a pose that never settles: steps of 1 cm growing by 1 % a round (no
  // extrapolation, since they do not shrink; the line search off).
  DenseRoundsSettings plain = twoGates();
  plain.line_search = false;
  Script endless;
  endless.step = [](int call) { return 0.01 * std::pow(1.01, call); };
  const RegistrationResult far = runDenseRounds(startAt(0.0), kPoints, plain, endless.ops(), rounds);
  EXPECT_EQ(rounds.run, 16);
  double sum = 0;
  for (int k = 0; k < 16; ++k) sum += 0.01 * std::pow(1.01, k);
  EXPECT_NEAR(xOf(far.T_target_source), sum, 1e-9);
}
