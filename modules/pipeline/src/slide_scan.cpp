#include "slide_scan.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>
#include <vector>

#include "gasp/core/error.h"

namespace gasp {

void validate(const SlideScanParams& p) {
  if (!(p.range_m > 0) || !std::isfinite(p.range_m)) throw Error("SlideScanParams: range_m must be finite and > 0");
  if (!(p.step_m > 0) || !(p.step_m <= p.range_m)) throw Error("SlideScanParams: step_m must be > 0 and <= range_m");
  if (!(p.min_gain >= 0 && p.min_gain <= 1)) throw Error("SlideScanParams: min_gain must be in [0, 1]");
  if (p.pixel_step < 1) throw Error("SlideScanParams: pixel_step must be >= 1");
}

std::string SlideScanReport::summary() const {
  if (!ran) return "not run";
  char buf[200];
  std::snprintf(buf, sizeof buf, "%s (agreement %.3f; best offset %+.2f m: %.3f", moved ? "moved" : "kept",
                agreement_before, offset_m, agreement_best);
  std::string s = buf;
  if (agreement_after >= 0) {
    std::snprintf(buf, sizeof buf, ", refined %.3f", agreement_after);
    s += buf;
  }
  return s + ")";
}

namespace detail {

namespace {

/// A pose moved along one unobservable direction of the patch problem: rotation omega about the
/// scene centre c and translation t, per unit offset, in the target frame.
struct SlideDirection {
  Eigen::Vector3d omega, t, centre;
  Isometry3 apply(const Isometry3& T, double s) const {
    Isometry3 shift = Isometry3::Identity();
    const Eigen::Vector3d w = s * omega;
    if (w.norm() > 0) shift.linear() = Eigen::AngleAxisd(w.norm(), w.normalized()).toRotationMatrix();
    shift.translation() = centre - shift.linear() * centre + s * t;
    return shift * T;
  }
};

}  // namespace

SlideScanOutcome scanSlide(const DepthView& source, const DepthView& target, const RegistrationResult& patch_pose,
                           const Isometry3& claimed, const std::function<RegistrationResult(const Isometry3&)>& refine_from,
                           const SlideScanParams& params, const FreeSpaceTest& free_space, bool partial_ok) {
  SlideScanOutcome out;
  const auto& basis = patch_pose.unobservable_directions;
  if (basis.cols() == 0 || source.segmentation.patches.empty()) return out;
  out.report.ran = true;
  const auto agree = [&](const Isometry3& T) { return depthAgreement(source, target, T, params.pixel_step); };
  out.report.agreement_before = agree(claimed);

  // Directions in the target frame from the conditioned basis (degeneracy.h): translation part
  // v_t [m] and rotation part v_r as arc length at the radius L, i.e. omega = v_r / L about c.
  const double L = std::max(patch_pose.scene_radius_m, kMinSceneRadiusM);
  std::vector<Eigen::Vector3d> centroids;  // the source patches in the target frame
  for (const auto& p : source.segmentation.patches)
    if (p.centroid.allFinite()) centroids.push_back(claimed * p.centroid);
  if (centroids.empty()) return out;

  // Every (direction, offset) start, then their agreements in parallel; the best is picked in
  // order, so the result does not depend on the threads.
  const int steps = static_cast<int>(std::floor(params.range_m / params.step_m + 1e-9));
  std::vector<std::pair<double, Isometry3>> starts;  // (offset, pose)
  for (int j = 0; j < basis.cols(); ++j) {
    SlideDirection dir{basis.col(j).tail<3>() / L, basis.col(j).head<3>(), patch_pose.scene_centre};
    // Offsets are RMS displacements of the source centroids (to first order).
    double sum2 = 0;
    for (const auto& p : centroids) sum2 += (dir.t + dir.omega.cross(p - dir.centre)).squaredNorm();
    const double unit = std::sqrt(sum2 / static_cast<double>(centroids.size()));
    if (!(unit > 1e-9)) continue;
    for (int k = -steps; k <= steps; ++k)
      if (k != 0) starts.emplace_back(k * params.step_m, dir.apply(claimed, k * params.step_m / unit));
  }
  std::vector<double> agreement(starts.size());
  tbb::parallel_for(std::size_t{0}, starts.size(), [&](std::size_t i) { agreement[i] = agree(starts[i].second); });
  double best = out.report.agreement_before;
  Isometry3 best_start = claimed;
  for (std::size_t i = 0; i < starts.size(); ++i)
    if (agreement[i] > best) {
      best = agreement[i];
      best_start = starts[i].second;
      out.report.offset_m = starts[i].first;
    }
  out.report.agreement_best = best;
  if (!(best > out.report.agreement_before + params.min_gain)) return out;

  RegistrationResult refined = refine_from(best_start);
  if (!(partial_ok ? refined.estimated() : refined.success)) return out;
  out.report.agreement_after = agree(refined.T_target_source);
  if (!(out.report.agreement_after > out.report.agreement_before + params.min_gain)) return out;
  VisibilityCheck check = free_space(refined.T_target_source);
  if (!check.passed) return out;
  out.report.moved = true;
  out.pose = std::move(refined);
  out.check = std::move(check);
  return out;
}

RegistrationResult planeSymmetries(const Eigen::Vector3d& normal, const Eigen::Vector3d& centroid, double radius_m) {
  RegistrationResult r;
  const Eigen::Vector3d n = normal.normalized(), u = n.unitOrthogonal(), v = n.cross(u);
  r.unobservable_directions = Eigen::Matrix<double, 6, 3>::Zero();
  r.unobservable_directions.col(0).head<3>() = u;
  r.unobservable_directions.col(1).head<3>() = v;
  r.unobservable_directions.col(2).tail<3>() = n;  // conditioned: a rotation about the centre
  r.scene_centre = centroid;
  r.scene_radius_m = radius_m;
  r.degenerate = true;
  return r;
}

}  // namespace detail
}  // namespace gasp
