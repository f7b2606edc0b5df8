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

/// The line search's verdict on the step from `pose` to `next` (the file's comment): stop (every
/// length scores worse, or the evaluation of a shortened step failed), or go on -- with the
/// shortened step's evaluation in `shortened` when the step was shortened. `there`: the terms
/// gathered where the accepted step lands (the next round's).
struct LineSearch {
  bool stop = false;
  std::optional<RegistrationResult> shortened;
  GatedTerms there;
};

LineSearch searchLine(const RegistrationResult& pose, const RegistrationResult& next, const GatedTerms& gathered,
                      const std::vector<Eigen::Vector3d>& points, int round, const DenseRoundsSettings& settings,
                      const DenseRoundsOps& ops) {
  LineSearch out;
  const double score_before = ops.score(gathered, pose.T_target_source);
  const Isometry3 full_step = next.T_target_source * pose.T_target_source.inverse();
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const auto& c : pointsAt(points, pose.T_target_source)) centre += c;
  if (!points.empty()) centre /= static_cast<double>(points.size());
  Isometry3 landing = next.T_target_source;
  out.there = ops.gather(landing, round + 1);
  double score_after = ops.score(out.there, landing);
  double fraction = 1.0;
  for (int halving = 0; score_after < score_before && halving < settings.line_search_halvings; ++halving) {
    fraction *= 0.5;
    landing = stepPower(full_step, centre, fraction) * pose.T_target_source;
    out.there = ops.gather(landing, round + 1);
    score_after = ops.score(out.there, landing);
  }
  const bool worse = score_after < score_before;
  if (!worse && fraction < 1.0) out.shortened = ops.solve(landing, out.there.terms, true);
  out.stop = worse || (out.shortened && !out.shortened->estimated());
  return out;
}

/// Extrapolation (Besl & McKay 1992, IV-C; step_extrapolation.h): two plain steps at the last gate
/// that move the pose the same way say it creeps; `pose` then jumps ahead along `step` (true).
/// Otherwise `step` becomes the previous step for the next round.
bool extrapolate(std::optional<Isometry3>& previous_step, const Isometry3& step, RegistrationResult& pose,
                 const std::vector<Eigen::Vector3d>& points, const DenseRoundsSettings& settings) {
  if (!previous_step) {
    previous_step = step;
    return false;
  }
  const StepExtrapolation jump =
      extrapolateSteps(*previous_step, step, pointsAt(points, pose.T_target_source), settings.extrapolation_max);
  if (jump.factor > 0.0) {
    pose.T_target_source = jump.jump * pose.T_target_source;
    previous_step.reset();
    return true;
  }
  previous_step = step;
  return false;
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
    if (!next.estimated()) {
      // The dense problem may be degenerate or fail where the patch problem was not: then no
      // pose is claimed (never a silently weaker one). A partial pose goes on: its rounds move
      // it in the observed directions only (refinement.h).
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
      LineSearch search = searchLine(pose, next, gathered, points, round, settings, ops);
      if (search.stop) {
        // The rounds end at the last refined pose (not at an extrapolated jump from it).
        rounds.line_search_stopped = true;
        rounds.last_step_m = 0.0;
        pose = std::move(last_refined);
        break;
      }
      if (search.shortened) {
        next = std::move(*search.shortened);
        step_m = rmsStep(points, pose.T_target_source, next.T_target_source);
        ++rounds.shortened;
        shortened = true;
      }
      gathered_ahead = std::move(search.there);
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
    // Extrapolation: never after the last round (the pose returned is always a refined one).
    if (round + 1 < settings.rounds || round < first_last_gate_round || round + 1 >= max_rounds ||
        settings.extrapolation_max <= 0.0)
      continue;
    if (extrapolate(previous_step, step, pose, points, settings)) gathered_ahead.reset();
  }
  return pose;
}

}  // namespace gasp
