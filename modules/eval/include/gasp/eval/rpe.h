#pragma once
/// \file rpe.h Relative pose error with a fixed delta, as the TUM RGB-D benchmark's
/// evaluate_rpe.py --fixed_delta defines it: for each estimated pose i, j is the estimated pose
/// whose index (unit "frames") or timestamp (unit "s") is closest to i's plus delta; pairs whose j
/// is the last pose are skipped (as the script does); the ground-truth poses nearest to both
/// stamps must lie within max_dt. With a (-) b = a^-1 b, P the estimate and Q the ground truth,
/// the error is E = (P_j (-) P_i)^-1 (Q_j (-) Q_i), exactly the script's
/// ominus(ominus(P_j, P_i), ominus(Q_j, Q_i)); translational error |trans(E)| [m], rotational
/// error angle(E) [deg].
#include <cstddef>
#include <vector>

#include "gasp/core/tum_trajectory.h"
#include "gasp/eval/error_statistics.h"

namespace gasp::eval {

enum class DeltaUnit { Frames, Seconds };

struct RpeOptions {
  double delta = 1.0;                  ///< step between the two poses of a pair
  DeltaUnit unit = DeltaUnit::Seconds;  ///< evaluate_rpe.py's default is 1 s
  double max_dt = 0.02;  ///< est-to-gt stamp tolerance [s] (the script: 2x the median gt period)
  double offset = 0.0;   ///< added to the estimate's timestamps [s]
  double scale = 1.0;    ///< multiplies the estimated relative translations
};

struct RpePair {
  std::size_t est_i = 0, est_j = 0;  ///< indices into the estimate
  std::size_t gt_i = 0, gt_j = 0;    ///< indices into the ground truth
  double translation_error = 0.0;    ///< [m]
  double rotation_error_deg = 0.0;   ///< [deg]
};

struct RpeResult {
  ErrorStatistics translation;   ///< [m]
  ErrorStatistics rotation_deg;  ///< [deg]
  std::vector<RpePair> pairs;
};

/// Throws gasp::Error when either trajectory is empty, fewer than 2 estimated poses have a
/// ground-truth pose within max_dt, delta is not positive, or no pair survives.
RpeResult computeRpe(const Trajectory& gt, const Trajectory& est, const RpeOptions& options = {});

}  // namespace gasp::eval
