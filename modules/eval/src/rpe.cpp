#include "gasp/eval/rpe.h"

#include <cmath>
#include <cstdio>
#include <string>

#include "gasp/core/error.h"

namespace gasp::eval {

RpeResult computeRpe(const Trajectory& gt, const Trajectory& est, const RpeOptions& options) {
  if (gt.empty() || est.empty()) throw Error("RPE: a trajectory is empty");
  if (!(options.delta > 0.0) || !std::isfinite(options.delta)) throw Error("RPE: delta must be a positive finite number");
  if (!(options.scale > 0.0) || !std::isfinite(options.scale)) throw Error("RPE: scale must be a positive finite number");
  if (options.unit == DeltaUnit::Frames && options.delta != std::floor(options.delta))
    throw Error("RPE: a delta in frames must be a whole number");
  std::vector<double> t_gt, t_est;
  for (const auto& p : gt) t_gt.push_back(p.timestamp);
  for (const auto& p : est) t_est.push_back(p.timestamp);

  auto gtIndexNear = [&](double t_e) -> std::optional<std::size_t> {
    const std::size_t k = findClosestIndex(t_gt, t_e + options.offset);
    if (std::abs(t_gt[k] - (t_e + options.offset)) > options.max_dt) return std::nullopt;
    return k;
  };
  std::size_t with_gt = 0;
  for (double t : t_est) with_gt += gtIndexNear(t) ? 1 : 0;
  if (with_gt < 2)
    throw Error("RPE: only " + std::to_string(with_gt) + " estimated pose(s) have ground truth within " +
                std::to_string(options.max_dt) + " s; at least 2 are needed (are these the right files?)");

  std::vector<double> index(est.size());
  for (std::size_t i = 0; i < est.size(); ++i)
    index[i] = options.unit == DeltaUnit::Frames ? static_cast<double>(i) : t_est[i];

  RpeResult r;
  std::vector<double> e_t, e_r;
  std::size_t self_pairs = 0;
  for (std::size_t i = 0; i < est.size(); ++i) {
    const std::size_t j = findClosestIndex(index, index[i] + options.delta);
    if (j == est.size() - 1) continue;  // evaluate_rpe.py drops pairs ending on the last pose
    if (j <= i) {  // a delta below the poses' spacing: a pose with itself measures nothing
      ++self_pairs;
      continue;
    }
    const auto gi = gtIndexNear(t_est[i]), gj = gtIndexNear(t_est[j]);
    if (!gi || !gj) continue;
    // evaluate_rpe.py: ominus(a, b) = a^-1 b; E = ominus(scale(ominus(P_j, P_i)), ominus(Q_j, Q_i)).
    Isometry3 A = est[j].T_world_camera.inverse() * est[i].T_world_camera;
    A.translation() *= options.scale;
    const Isometry3 B = gt[*gj].T_world_camera.inverse() * gt[*gi].T_world_camera;
    const Isometry3 error = A.inverse() * B;
    RpePair p{i, j, *gi, *gj, error.translation().norm(), rotationAngle(error) * 180.0 / M_PI};
    if (!std::isfinite(p.translation_error) || !std::isfinite(p.rotation_error_deg))
      throw Error("RPE: the errors are not finite (translations beyond floating point after the scale?)");
    e_t.push_back(p.translation_error);
    e_r.push_back(p.rotation_error_deg);
    r.pairs.push_back(p);
  }
  if (r.pairs.empty()) {
    char delta[32];
    std::snprintf(delta, sizeof delta, "%g", options.delta);
    throw Error("RPE: no pose pair at delta " + std::string(delta) + (options.unit == DeltaUnit::Frames ? " frames" : " s") +
                (self_pairs > 0 ? ": the delta is below the poses' spacing (each pose would pair with itself)"
                                : " has ground truth"));
  }
  r.translation = computeStatistics(std::move(e_t));
  r.rotation_deg = computeStatistics(std::move(e_r));
  return r;
}

}  // namespace gasp::eval
