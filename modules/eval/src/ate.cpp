#include "gasp/eval/ate.h"

#include <Eigen/Geometry>

#include <cmath>

#include "gasp/core/error.h"

namespace gasp::eval {

AteResult computeAte(const Trajectory& gt, const Trajectory& est, const AteOptions& options) {
  if (!(options.scale > 0.0) || !std::isfinite(options.scale)) throw Error("ATE: scale must be a positive finite number");
  std::vector<double> t_gt, t_est;
  for (const auto& p : gt) t_gt.push_back(p.timestamp);
  for (const auto& p : est) t_est.push_back(p.timestamp);
  AteResult r;
  r.matches = associateTimestamps(t_gt, t_est, options.max_dt, options.offset);
  if (r.matches.size() < 3)
    throw Error("ATE: only " + std::to_string(r.matches.size()) +
                " pose pair(s) have timestamps within " + std::to_string(options.max_dt) +
                " s; at least 3 are needed (are these the right files?)");

  const auto n = static_cast<Eigen::Index>(r.matches.size());
  Eigen::Matrix3Xd p_gt(3, n), p_est(3, n);
  for (Eigen::Index k = 0; k < n; ++k) {
    const auto& [i, j] = r.matches[static_cast<std::size_t>(k)];
    p_gt.col(k) = gt[i].T_world_camera.translation();
    p_est.col(k) = options.scale * est[j].T_world_camera.translation();
  }
  // Least-squares rigid alignment est -> gt (no scale), as evaluate_ate.py's align().
  r.T_gt_est.matrix() = Eigen::umeyama(p_est, p_gt, false);
  std::vector<double> errors(static_cast<std::size_t>(n));
  for (Eigen::Index k = 0; k < n; ++k)
    errors[static_cast<std::size_t>(k)] = (r.T_gt_est * p_est.col(k) - p_gt.col(k)).norm();
  for (double e : errors)
    if (!std::isfinite(e))
      throw Error("ATE: the position errors are not finite (positions beyond floating point after the scale?)");
  r.errors = errors;
  r.translation = computeStatistics(std::move(errors));
  return r;
}

}  // namespace gasp::eval
