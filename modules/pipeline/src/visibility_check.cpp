#include "gasp/pipeline/visibility_check.h"

#include "free_space_verdict.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>

#include <opencv2/imgproc.hpp>

#include "gasp/core/depth_image.h"
#include "gasp/core/error.h"

namespace gasp {

void validate(const VisibilityCheckParams& p) {
  if (p.pixel_step < 1) throw Error("VisibilityCheckParams: pixel_step must be >= 1");
  if (!(p.gate_m > 0) || !(p.gate_per_m2 >= 0) || !std::isfinite(p.gate_m) || !std::isfinite(p.gate_per_m2))
    throw Error("VisibilityCheckParams: gate_m must be > 0 and gate_per_m2 >= 0, both finite");
  if (!(p.max_violation_ratio >= 0 && p.max_violation_ratio <= 1))
    throw Error("VisibilityCheckParams: max_violation_ratio must be in [0, 1]");
  if (!(p.max_occluded_ratio >= 0 && p.max_occluded_ratio <= 1))
    throw Error("VisibilityCheckParams: max_occluded_ratio must be in [0, 1]");
  if (!(p.max_two_way_violation_ratio >= 0 && p.max_two_way_violation_ratio <= 1))
    throw Error("VisibilityCheckParams: max_two_way_violation_ratio must be in [0, 1]");
  if (p.min_consistent < 0) throw Error("VisibilityCheckParams: min_consistent must be >= 0");
}

FreeSpaceGate::FreeSpaceGate(const DepthView& to, const VisibilityCheckParams& params)
    : to_(to),
      params_(params),
      half_pixel_rad_(to.projection.halfPixelDiagonalRad()),
      min_cos_(std::cos(to.superpixels.max_incidence_deg * M_PI / 180.0)) {}

double FreeSpaceGate::operator()(int u, int v, const Eigen::Vector3d& q, double z_t) const {
  const double gate = params_.gate_m + params_.gate_per_m2 * z_t * z_t;
  if (!params_.pixel_spread) return gate;
  const cv::Mat& labels = to_.segmentation.labels;
  if (labels.rows != to_.depth_m.rows || labels.cols != to_.depth_m.cols) return gate;
  if (u < 0 || v < 0 || u >= labels.cols || v >= labels.rows) return gate;
  const int label = labels.at<int>(v, u);
  if (label < 0 || static_cast<std::size_t>(label) >= to_.segmentation.patches.size()) return gate;
  const double len = q.norm();
  if (!(len > 0.0)) return gate;
  const double c = std::max(std::abs(to_.segmentation.patches[static_cast<std::size_t>(label)].normal.dot(q)) / len, min_cos_);
  return gate + z_t * half_pixel_rad_ * std::sqrt(std::max(0.0, 1.0 - c * c)) / c;
}

namespace {

using Counts = detail::FreeSpaceCounts;

/// `regions`: also the largest 8-connected region of the violating samples (not for depthAgreement).
Counts countOneWay(const DepthView& from, const DepthView& to, const Isometry3& T_to_from, const VisibilityCheckParams& p,
                   bool regions) {
  Counts c;
  const FreeSpaceGate gate_at(to, p);
  const cv::Mat& d = from.depth_m;
  // The violating samples on the sampling grid, for their largest 8-connected region.
  cv::Mat grid;
  if (regions) grid = cv::Mat::zeros((d.rows + p.pixel_step - 1) / p.pixel_step, (d.cols + p.pixel_step - 1) / p.pixel_step, CV_8U);
  for (int v = 0; v < d.rows; v += p.pixel_step)
    for (int u = 0; u < d.cols; u += p.pixel_step) {
      const float z0 = d.at<float>(v, u);
      if (!isValidDepth(z0)) continue;
      const Eigen::Vector3d q = T_to_from * from.projection.unproject(u, v, z0);
      double uf = 0, vf = 0;
      if (!to.projection.project(q, uf, vf)) continue;
      const int ut = static_cast<int>(std::lround(uf)), vt = static_cast<int>(std::lround(vf));
      if (ut < 0 || vt < 0 || ut >= to.depth_m.cols || vt >= to.depth_m.rows) continue;
      const float zt = to.depth_m.at<float>(vt, ut);
      if (!isValidDepth(zt)) continue;
      const double zq = to.projection.depth(q);
      const double gate = gate_at(ut, vt, q, zt);
      if (std::abs(zq - zt) <= gate) ++c.consistent;
      else if (zq > zt) ++c.occluded;
      else {
        ++c.violations;
        if (regions) grid.at<std::uint8_t>(v / p.pixel_step, u / p.pixel_step) = 1;
      }
    }
  if (regions && c.violations > 0) {
    cv::Mat labels, stats, centroids;
    const int n = cv::connectedComponentsWithStats(grid, labels, stats, centroids, 8, CV_32S);
    int largest = 0;
    for (int k = 1; k < n; ++k) largest = std::max(largest, stats.at<int>(k, cv::CC_STAT_AREA));
    c.largest_blob_share = static_cast<double>(largest) / c.violations;
  }
  return c;
}

VisibilityCheck check(const DepthView& source, const DepthView& target, const Isometry3& T_target_source,
                      const VisibilityCheckParams& p, bool regions) {
  validate(p);
  VisibilityCheck out;
  if (!T_target_source.matrix().allFinite()) {
    out.reason = "the pose is not finite";
    return out;
  }
  const Counts st = countOneWay(source, target, T_target_source, p, regions);
  const Counts ts = countOneWay(target, source, T_target_source.inverse(), p, regions);
  detail::decideFreeSpace(st, ts, p, {"visibility check", "samples", "view"}, out);
  return out;
}

}  // namespace

VisibilityCheck checkVisibility(const DepthView& source, const DepthView& target, const Isometry3& T_target_source,
                                const VisibilityCheckParams& p) {
  return check(source, target, T_target_source, p, true);
}

VisibilityCheckParams agreementParams(int pixel_step) {
  VisibilityCheckParams p;
  p.pixel_step = pixel_step;
  p.gate_m = 0.01;
  p.gate_per_m2 = 0.005;
  p.max_violation_ratio = 1.0;
  p.max_occluded_ratio = 1.0;
  p.max_two_way_violation_ratio = 1.0;
  p.min_consistent = 0;
  return p;
}

double depthAgreement(const DepthView& source, const DepthView& target, const Isometry3& T_target_source,
                      int pixel_step) {
  return check(source, target, T_target_source, agreementParams(pixel_step), false).consistentShare();
}

}  // namespace gasp
