#include "gasp/pipeline/dense_rounds.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <utility>

#include "gasp/core/error.h"
#include "gasp/pipeline/step_extrapolation.h"

namespace gasp {

namespace {

std::vector<Eigen::Vector3d> pointsAt(const std::vector<Eigen::Vector3d>& points, const Isometry3& T) {
  std::vector<Eigen::Vector3d> mapped;
  mapped.reserve(points.size());
  for (const auto& p : points) mapped.push_back(T * p);
  return mapped;
}

/// RMS displacement of `points` from `before` to `after` (0 without points).
double rmsStep(const std::vector<Eigen::Vector3d>& points, const Isometry3& before, const Isometry3& after) {
  if (points.empty()) return 0.0;
  double sum2 = 0;
  for (const auto& p : points) sum2 += (after * p - before * p).squaredNorm();
  return std::sqrt(sum2 / static_cast<double>(points.size()));
}

}  // namespace

void validate(const DenseRoundsSettings& s) {
  if (s.gates_m.empty()) throw Error("dense rounds: no gates");
  for (const double g : s.gates_m)
    if (!std::isfinite(g) || g <= 0.0) throw Error("dense rounds: gates must be finite and positive, got " + std::to_string(g));
  if (s.rounds < 0 || s.max_rounds < 0) throw Error("dense rounds: rounds and max_rounds must be >= 0");
  if (s.line_search_halvings < 0) throw Error("dense rounds: line_search_halvings must be >= 0");
  if (!std::isfinite(s.converged_m) || s.converged_m < 0.0) throw Error("dense rounds: converged_m must be finite and >= 0");
  if (!std::isfinite(s.extrapolation_max) || s.extrapolation_max < 0.0)
    throw Error("dense rounds: extrapolation_max must be finite and >= 0");
}

RegistrationResult runDenseRounds(const RegistrationResult& start, const std::vector<Eigen::Vector3d>& points,
                                  const DenseRoundsSettings& settings, const DenseRoundsOps& ops, DenseRounds& rounds) {
  validate(settings);
  if (!ops.gather || !ops.solve || !ops.score) throw Error("dense rounds: gather, solve and score are all needed");
  rounds = DenseRounds{};
  RegistrationResult pose = start;
  const int max_rounds = std::max(settings.rounds, settings.max_rounds);
  const int first_last_gate_round = static_cast<int>(settings.gates_m.size()) - 1;
  std::optional<Isometry3> previous_step;    // the last round's motion, when it was a plain round at the last gate
  std::optional<GatedTerms> gathered_ahead;  // the terms at `pose`, when the line search gathered them
  RegistrationResult last_refined = pose;    // the last round's result (`pose` may be an extrapolated jump from it)
  for (int round = 0; round < max_rounds; ++round) {
    const GatedTerms gathered = gathered_ahead ? std::move(*gathered_ahead) : ops.gather(pose.T_target_source, round);
    gathered_ahead.reset();
    rounds.terms = static_cast<int>(gathered.terms.size());
    rounds.run = round + 1;
    RegistrationResult next = ops.solve(pose.T_target_source, gathered.terms, false);
    if (!next.success) {
      // The dense problem may be degenerate or fail where the patch problem was not: then no
      // pose is claimed (never a silently weaker one).
      next.reason = "dense refinement: " + next.reason;
      pose = std::move(next);
      break;
    }
    double step_m = rmsStep(points, pose.T_target_source, next.T_target_source);
    // Line search (the file's comment). Shrinking steps are left alone: there the rounds creep,
    // and the extrapolation below acts.
    bool shortened = false;
    if (settings.line_search && round >= first_last_gate_round && step_m >= settings.converged_m &&
        rounds.last_step_m >= 0.0 && step_m > rounds.last_step_m) {
      const double score_before = ops.score(gathered, pose.T_target_source);
      const Isometry3 full_step = next.T_target_source * pose.T_target_source.inverse();
      Eigen::Vector3d centre = Eigen::Vector3d::Zero();
      for (const auto& c : pointsAt(points, pose.T_target_source)) centre += c;
      if (!points.empty()) centre /= static_cast<double>(points.size());
      Isometry3 landing = next.T_target_source;
      GatedTerms there = ops.gather(landing, round + 1);
      double score_after = ops.score(there, landing);
      double fraction = 1.0;
      for (int halving = 0; score_after < score_before && halving < settings.line_search_halvings; ++halving) {
        fraction *= 0.5;
        landing = stepPower(full_step, centre, fraction) * pose.T_target_source;
        there = ops.gather(landing, round + 1);
        score_after = ops.score(there, landing);
      }
      const bool worse = score_after < score_before;
      std::optional<RegistrationResult> at;
      if (!worse && fraction < 1.0) at = ops.solve(landing, there.terms, true);
      if (worse || (at && !at->success)) {
        // The rounds end at the last refined pose (not at an extrapolated jump from it).
        rounds.line_search_stopped = true;
        rounds.last_step_m = 0.0;
        pose = std::move(last_refined);
        break;
      }
      if (at) {
        next = std::move(*at);
        step_m = rmsStep(points, pose.T_target_source, next.T_target_source);
        ++rounds.shortened;
        shortened = true;
      }
      gathered_ahead = std::move(there);
    }
    const Isometry3 step = next.T_target_source * pose.T_target_source.inverse();
    rounds.last_step_m = step_m;
    pose = std::move(next);
    last_refined = pose;
    // A shortened step is no sign of convergence (the solve wanted to go further), nor a step
    // to extrapolate (it points where the full step was refused).
    if (shortened) {
      previous_step.reset();
      continue;
    }
    if (round + 1 >= settings.rounds && rounds.last_step_m < settings.converged_m) break;
    // Extrapolation (Besl & McKay 1992, IV-C; step_extrapolation.h): two rounds at the last
    // gate that move the pose the same way say it creeps; the next round starts ahead along the
    // last step. Never after the last round: the pose returned is always a refined one.
    if (round + 1 < settings.rounds || round < first_last_gate_round || round + 1 >= max_rounds ||
        settings.extrapolation_max <= 0.0)
      continue;
    if (!previous_step) {
      previous_step = step;
      continue;
    }
    const StepExtrapolation jump =
        extrapolateSteps(*previous_step, step, pointsAt(points, pose.T_target_source), settings.extrapolation_max);
    if (jump.factor > 0.0) {
      pose.T_target_source = jump.jump * pose.T_target_source;
      previous_step.reset();
      gathered_ahead.reset();
    } else {
      previous_step = step;
    }
  }
  return pose;
}

}  // namespace gasp
