// The dense rounds' convergence rule (PairParams::dense_max_rounds, dense_converged_m): after
// the rounds of dense_gates_m, more rounds at the last gate until the source patches move by less
// than dense_converged_m in one round.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <tuple>

#include "gasp/core/error.h"
#include "gasp/pipeline/pair_registration.h"
#include "synthetic_pairs.h"

using namespace gasp;

namespace {

using test::makePair;
using test::Pair;
using test::rotationErrorDeg;
using test::translationError;

}  // namespace

TEST(DenseRounds, RoundsUntilConvergedBringSlowlySlidingPosesToTheTruth) {
  // Noise seeds 2 and 3 of the synthetic scenes (docs/pipeline.md, "Converged dense rounds"):
  // only small objects pin a slide along the floor and the wall, and each round at the last gate
  // moves the pose millimetres to centimetres towards the truth. Three rounds left these
  // 2.1-5.3 cm / 0.56-0.96 deg off; rounds until converged (with the slide scan) bring them within
  // 1.5 cm / 0.4 deg.
  for (const auto& [scene, seed, from, to] :
       {std::tuple{"repeated", 2, 0, 10}, std::tuple{"sparse", 2, 0, 15}, std::tuple{"sparse", 2, 12, 27},
        std::tuple{"repeated", 3, 6, 12}}) {
    const Pair p = makePair(scene, from, to, static_cast<std::uint64_t>(seed));
    const std::string name = std::string(scene) + " seed " + std::to_string(seed) + " " + std::to_string(from) +
                             " -> " + std::to_string(to);
    PairParams three;
    three.refine.dense.max_rounds = three.refine.dense.rounds;
    // The visibility limit as it was when these poses were measured (30 %). With today's 15 %,
    // sparse 0 -> 15 takes another path through the checks and three rounds end 2 mm off.
    three.certify.visibility.max_violation_ratio = 0.3;
    const PairResult before = registerViews(p.a, p.b, three);
    ASSERT_TRUE(before.pose.success) << name << ": " << before.pose.reason;
    EXPECT_GT(translationError(p, before), 0.02) << name << ": three rounds stop short";
    EXPECT_EQ(before.dense_rounds_run, 3) << name;

    const PairResult r = registerViews(p.a, p.b);
    ASSERT_TRUE(r.pose.success) << name << ": " << r.pose.reason;
    EXPECT_LT(translationError(p, r), 0.02) << name;
    EXPECT_LT(rotationErrorDeg(p, r), 1.0) << name;
    EXPECT_TRUE(r.visibility.passed) << name;
    EXPECT_GE(r.dense_rounds_run, 1) << name;
    EXPECT_LE(r.dense_rounds_run, PairParams{}.refine.dense.max_rounds) << name;
  }
}

TEST(DenseRounds, StopWhenThePoseStopsMoving) {
  const Pair p = makePair("room", 42, 48);
  const PairParams defaults;
  const PairResult r = registerViews(p.a, p.b);
  ASSERT_TRUE(r.pose.success) << r.pose.reason;
  EXPECT_LT(translationError(p, r), 0.02);
  // Converged before the limit: the last round moved the patches less than the threshold.
  EXPECT_GE(r.dense_rounds_run, defaults.refine.dense.rounds);
  EXPECT_LT(r.dense_rounds_run, defaults.refine.dense.max_rounds);
  EXPECT_GE(r.dense_last_step_m, 0.0);
  EXPECT_LT(r.dense_last_step_m, defaults.refine.dense.converged_m);

  // A threshold of 0 never converges: every allowed round runs.
  PairParams never = defaults;
  never.refine.dense.converged_m = 0.0;
  never.refine.slide_scan.enabled = false;  // the rounds reported are then the first refinement's
  never.refine.dense.line_search = false;   // which could end the rounds before a worse step
  const PairResult all = registerViews(p.a, p.b, never);
  ASSERT_TRUE(all.pose.success) << all.pose.reason;
  EXPECT_EQ(all.dense_rounds_run, defaults.refine.dense.max_rounds);
  EXPECT_LT(translationError(p, all), 0.02);

  // dense_max_rounds at or below dense_rounds: exactly dense_rounds rounds, whatever the step.
  PairParams fixed = defaults;
  fixed.refine.dense.max_rounds = 0;
  fixed.refine.dense.converged_m = 1.0;  // would stop after the first round if the gates' rounds could stop
  const PairResult three = registerViews(p.a, p.b, fixed);
  ASSERT_TRUE(three.pose.success) << three.pose.reason;
  EXPECT_EQ(three.dense_rounds_run, defaults.refine.dense.rounds);

  // No dense rounds: nothing reported.
  PairParams none = defaults;
  none.refine.dense.rounds = 0;
  none.refine.dense.max_rounds = 0;
  const PairResult patch_only = registerViews(p.a, p.b, none);
  EXPECT_EQ(patch_only.dense_rounds_run, 0);
  EXPECT_EQ(patch_only.dense_last_step_m, -1.0);
}

TEST(DenseRounds, InvalidParametersThrow) {
  const Pair p = makePair("room", 42, 48);
  const auto throwsFor = [&](auto change) {
    PairParams params;
    change(params);
    EXPECT_THROW(registerViews(p.a, p.b, params), Error);
  };
  throwsFor([](PairParams& q) { q.refine.dense.max_rounds = -1; });
  throwsFor([](PairParams& q) { q.refine.dense.converged_m = -0.001; });
  throwsFor([](PairParams& q) { q.refine.dense.converged_m = std::numeric_limits<double>::quiet_NaN(); });
  throwsFor([](PairParams& q) { q.refine.dense.converged_m = std::numeric_limits<double>::infinity(); });
  throwsFor([](PairParams& q) { q.refine.dense.line_search_halvings = -1; });
}

TEST(DenseRounds, ExtrapolationCatchesACreepingPose) {
  // Noise seed 2 of the sparse scene, 0 -> 10: the patch pose is 35 cm off along the floor, and
  // each round at the last gate moves the pose 1-2.5 cm further the same way. Without the
  // extrapolation (and without the slide scan, which otherwise finds the rest) eight rounds end
  // 8 cm off, still moving; with it, two jumps along the rounds' steps bring the pose within
  // 1.5 cm / 0.5 deg in as many rounds (step_extrapolation.h).
  const Pair p = makePair("sparse", 0, 10, 2);
  PairParams plain;
  plain.refine.slide_scan.enabled = false;
  plain.refine.dense.extrapolation_max = 0.0;
  plain.refine.dense.max_rounds = 8;
  const PairResult creeping = registerViews(p.a, p.b, plain);
  ASSERT_TRUE(creeping.pose.success) << creeping.pose.reason;
  EXPECT_GT(translationError(p, creeping), 0.05);
  EXPECT_EQ(creeping.dense_rounds_run, plain.refine.dense.max_rounds);
  EXPECT_GT(creeping.dense_last_step_m, plain.refine.dense.converged_m);

  PairParams extrapolated = plain;
  extrapolated.refine.dense.extrapolation_max = PairParams{}.refine.dense.extrapolation_max;
  const PairResult r = registerViews(p.a, p.b, extrapolated);
  ASSERT_TRUE(r.pose.success) << r.pose.reason;
  EXPECT_LT(translationError(p, r), 0.015);
  EXPECT_LT(rotationErrorDeg(p, r), 0.5);
  EXPECT_TRUE(r.visibility.passed);
}

TEST(DenseRounds, InvalidExtrapolationThrows) {
  const Pair p = makePair("room", 42, 48);
  for (const double bad : {-1.0, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    PairParams params;
    params.refine.dense.extrapolation_max = bad;
    EXPECT_THROW(registerViews(p.a, p.b, params), Error) << bad;
  }
}

TEST(DenseRounds, LineSearchKeepsTheRoundsFromOvershooting) {
  // Synthetic pairs whose rounds at the last gate take a step longer than the one before that
  // lands where the views agree less (docs/pipeline.md, "Line search"): without the line search
  // the rounds go on from there and end 1.1-1.6 cm off; with it that step is shortened or
  // refused, and the rounds end within 0.75 cm, in fewer rounds.
  for (const auto& [scene, seed, from, to] :
       {std::tuple{"room", 1, 45, 48}, std::tuple{"room", 2, 51, 54}, std::tuple{"sparse", 1, 30, 33}}) {
    const Pair p = makePair(scene, from, to, static_cast<std::uint64_t>(seed));
    const std::string name = std::string(scene) + " seed " + std::to_string(seed) + " " + std::to_string(from) +
                             " -> " + std::to_string(to);
    PairParams plain;
    plain.refine.dense.line_search = false;
    const PairResult overshot = registerViews(p.a, p.b, plain);
    ASSERT_TRUE(overshot.pose.success) << name << ": " << overshot.pose.reason;
    EXPECT_GT(translationError(p, overshot), 0.01) << name;
    EXPECT_EQ(overshot.dense_steps_shortened, 0) << name;
    EXPECT_FALSE(overshot.dense_line_search_stopped) << name;

    const PairResult r = registerViews(p.a, p.b);
    ASSERT_TRUE(r.pose.success) << name << ": " << r.pose.reason;
    EXPECT_LT(translationError(p, r), 0.0075) << name;
    EXPECT_LT(rotationErrorDeg(p, r), 0.3) << name;
    EXPECT_TRUE(r.dense_steps_shortened > 0 || r.dense_line_search_stopped) << name;
    EXPECT_LT(r.dense_rounds_run, overshot.dense_rounds_run) << name;
    if (r.dense_line_search_stopped) {
      EXPECT_EQ(r.dense_last_step_m, 0.0) << name;
    }
  }
}
