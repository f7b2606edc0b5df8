#pragma once
/// \file pair_protocol.h The paper's pair benchmark protocol (Table II of gasp-paper.tex, NOTES
/// "Evaluation protocol"): pairs (i, i + skip) from regularly spaced start frames, a relative pose
/// per pair from some method, compared with ground truth. Method-agnostic: GASP and every
/// baseline are scored by the same code.
///
/// Definitions (docs/evaluation.md):
/// - frame indices count frames in depth.txt order (in a keyframe folder skip 1 = next keyframe);
/// - failure = the method returned no estimate;
/// - RMSE is over the returned estimates, so a wrong estimate counts in full;
/// - error of an estimate T_est (= T_b_a, maps frame-a points into frame b) against the truth
///   T_gt: E = T_gt^-1 T_est; translational error |trans(E)| [m], rotational error angle(E) [deg].
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "gasp/core/pose.h"

namespace gasp::eval {

/// Pairs (i, i + skip) for i = 0, starts_every, 2 starts_every, ... while i + skip < num_frames.
/// Throws gasp::Error for skip < 1 or starts_every < 1.
std::vector<std::pair<std::size_t, std::size_t>> makePairs(std::size_t num_frames, std::size_t skip,
                                                           std::size_t starts_every);

/// The outcome of one pair for one method.
struct PairOutcome {
  std::size_t skip = 0, from = 0, to = 0;
  bool estimated = false;        ///< false = failure (no estimate)
  double t_err_m = 0, r_err_deg = 0;  ///< only meaningful when estimated
  double ms = 0;                 ///< wall-clock time for the pair
  std::string reason;            ///< why no estimate (or a degeneracy note)
};

/// Error of an estimated relative pose against the truth (definition above).
void scorePose(const Isometry3& T_est, const Isometry3& T_gt, PairOutcome& outcome);

/// One row of the benchmark table.
struct SkipSummary {
  std::size_t skip = 0;
  std::string method;
  std::size_t pairs = 0, failed = 0;
  double rmse_t_m = 0, rmse_r_deg = 0;  ///< over the estimates (NaN when there is none)
  double fail_pct = 0;
  double within_pct = 0;  ///< share of ALL pairs with an estimate within 5 cm and 2 deg [%]
  double median_ms = 0;
};

/// Thresholds of SkipSummary::within_pct.
inline constexpr double kWithinTranslationM = 0.05, kWithinRotationDeg = 2.0;

/// Summary of the outcomes of one skip and one method.
SkipSummary summarise(const std::vector<PairOutcome>& outcomes, std::size_t skip, const std::string& method);

/// CSV header and row, columns skip,method,pairs,failed,rmse_t_m,rmse_r_deg,fail_pct,
/// within_5cm_2deg_pct,median_ms; the two RMSE cells are empty when no pair was estimated.
std::string csvHeader();
std::string csvRow(const SkipSummary& s);

}  // namespace gasp::eval
