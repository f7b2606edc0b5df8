#pragma once
/// \file dense_rounds.h The control of the dense rounds (docs/pipeline.md, step 4): which pose each
/// round starts from, when the rounds stop, when a step is shortened or refused. The terms and
/// the solve are the caller's (the refine stage, refine_stage.cpp, gathers projective pixel terms and edge terms
/// and solves with refinePose); here they are two functions, so that the control can be tested
/// on scripted steps.
///
/// Round r gathers its terms at the current pose with the gate gates_m[min(r, last)] and solves
/// from that pose. A round's step is the RMS displacement of `points` (the source patch
/// centroids). After the first `rounds` rounds, the rounds end when a step is below converged_m,
/// or after max_rounds rounds.
///
/// Line search (truncated_score.h), at the last gate: a step of at least converged_m that is
/// longer than the round before is judged afresh. The terms are gathered where it lands, and its score there must not be below
/// the score of the pose it leaves against that pose's terms (an equal score is kept). It is
/// halved (stepPower about the points' centre) up to line_search_halvings times; when every
/// length scores worse, the rounds end at the last refined pose (line_search_stopped, last_step_m
/// 0). A shortened step is evaluated there (the solve with no iterations: its information and
/// residuals are those of the pose returned); when that evaluation fails, the rounds stop in the
/// same way. A shortened step neither ends the rounds as converged nor seeds an extrapolation.
/// The terms gathered where an accepted step lands are the next round's.
///
/// Extrapolation (step_extrapolation.h), at the last gate after the first `rounds` rounds, and
/// never after the last round: two successive plain steps that agree and shrink move the pose
/// ahead along the newer one. The pose returned is always a refined one, never a jump.
#include <functional>
#include <vector>

#include <Eigen/Core>

#include "gasp/core/pose.h"
#include "gasp/pipeline/truncated_score.h"
#include "gasp/registration/correspondence.h"
#include "gasp/registration/registration_result.h"

namespace gasp {

/// The rounds' settings (RefineParams::dense, refine_stage.h; docs/pipeline.md step 4).
struct DenseRoundsSettings {
  std::vector<double> gates_m = {0.10, 0.05, 0.03};  ///< gate of round r: gates_m[min(r, size - 1)] [m]; not empty
  int rounds = 3;                   ///< rounds always run (>= 0; 0: the refine stage runs no dense refinement)
  int max_rounds = 16;              ///< at most max(rounds, max_rounds) rounds
  double converged_m = 0.002;       ///< a step below this ends the rounds [m]
  double extrapolation_max = 4.0;   ///< largest extrapolation factor (<= 0: off)
  bool line_search = true;
  int line_search_halvings = 3;
};

/// What the rounds did.
struct DenseRounds {
  int terms = 0;              ///< terms of the last round
  int run = 0;                ///< rounds run
  double last_step_m = -1.0;  ///< RMS displacement of the points in the last round (-1: none succeeded; 0: the line search stopped the rounds)
  int shortened = 0;          ///< steps the line search shortened
  bool line_search_stopped = false;  ///< every length of the last round's step scored worse: the rounds ended before it
};

/// The caller's terms and solve.
struct DenseRoundsOps {
  /// The terms at T_target_source with round `round`'s gate.
  std::function<GatedTerms(const Isometry3& T_target_source, int round)> gather;
  /// The pose solved from `start` on `terms`; with evaluate_only, no iterations: the result at
  /// `start` (information, residuals, degeneracy). A plain solve that claims neither a full nor a partial pose ends the rounds
  /// with that result; an evaluation's ends them at the last refined pose (a line-search stop).
  std::function<RegistrationResult(const Isometry3& start, const std::vector<PointToPlane>& terms, bool evaluate_only)> solve;
  /// The line search's score of a pose against terms gathered at it; larger is better.
  std::function<double(const GatedTerms& terms, const Isometry3& T_target_source)> score = truncatedScore;
};

/// Throws gasp::Error naming the first invalid setting: gates_m empty or not finite and positive,
/// rounds or max_rounds or line_search_halvings negative, converged_m or extrapolation_max not
/// finite or negative.
void validate(const DenseRoundsSettings& settings);

/// The rounds from `start` (its pose; its other fields are returned when no round runs).
/// `points`: the source points whose RMS displacement is a step (finite). A failed solve is
/// returned with "dense refinement: " before its reason. Throws gasp::Error for invalid settings
/// (validate()) or a missing gather, solve or score.
RegistrationResult runDenseRounds(const RegistrationResult& start, const std::vector<Eigen::Vector3d>& points,
                                  const DenseRoundsSettings& settings, const DenseRoundsOps& ops, DenseRounds& rounds);

}  // namespace gasp
