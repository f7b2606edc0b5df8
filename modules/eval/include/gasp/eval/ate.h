#pragma once
/// \file ate.h Absolute trajectory error, as the TUM RGB-D benchmark's evaluate_ate.py defines it:
/// timestamps associated one-to-one (associate.py, |t_gt - (t_est + offset)| < max_dt), the
/// estimated positions aligned to the ground truth by the least-squares rigid transform without
/// scale (Horn 1987 / Umeyama 1991), then statistics of the remaining position differences.
#include <utility>
#include <vector>

#include "gasp/core/tum_trajectory.h"
#include "gasp/eval/error_statistics.h"

namespace gasp::eval {

struct AteOptions {
  double max_dt = 0.02;  ///< association window [s] (evaluate_ate.py --max_difference)
  double offset = 0.0;   ///< added to the estimate's timestamps [s] (--offset)
  double scale = 1.0;    ///< multiplies the estimated positions (--scale)
};

struct AteResult {
  ErrorStatistics translation;  ///< absolute_translational_error [m]
  Isometry3 T_gt_est = Isometry3::Identity();  ///< alignment applied to the estimate
  std::vector<std::pair<std::size_t, std::size_t>> matches;  ///< (index in gt, index in est)
  std::vector<double> errors;  ///< per matched pair [m], in matches order
};

/// Throws gasp::Error when fewer than 3 pose pairs can be associated (the alignment is then
/// undetermined); the message says how many were found and the window used.
AteResult computeAte(const Trajectory& gt, const Trajectory& est, const AteOptions& options = {});

}  // namespace gasp::eval
