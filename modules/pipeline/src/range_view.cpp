#include "gasp/pipeline/range_view.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "gasp/core/error.h"
#include "gasp/superpixels/depth_superpixels.h"

namespace gasp {

namespace {

/// The columns' signed azimuth step, checked to be even (within a hundredth of a step).
double evenAzimuthStep(const RangeScan& scan) {
  const std::vector<double>& a = scan.azimuth_rad;
  if (a.size() < 2) return 2.0 * M_PI;  // one column: a whole turn's width is never binned
  auto wrapped = [](double d) { return std::remainder(d, 2.0 * M_PI); };
  const double step = wrapped(a[1] - a[0]);
  if (!(std::abs(step) > 0.0)) throw Error("range scan: the first two columns have the same azimuth");
  for (std::size_t i = 1; i < a.size(); ++i)
    if (std::abs(wrapped(a[i] - a[i - 1]) - step) > 0.01 * std::abs(step))
      throw Error("range scan: the azimuths are not evenly spaced (column " + std::to_string(i) + ")");
  return step;
}

}  // namespace

int rangeBinColumns(const RangeScan& scan) {
  if (scan.elevation_rad.size() < 2 || scan.azimuth_rad.size() < 2) return 1;
  const double pitch = (scan.elevation_rad.back() - scan.elevation_rad.front()) / static_cast<double>(scan.elevation_rad.size() - 1);
  const double step = std::abs(std::remainder(scan.azimuth_rad[1] - scan.azimuth_rad[0], 2.0 * M_PI));
  if (!(step > 0.0) || !(pitch > 0.0)) return 1;
  return std::max(1, static_cast<int>(std::lround(pitch / step)));
}

std::pair<cv::Mat, ViewProjection> binRangeScan(const RangeScan& scan, const SmoothSurfaceParams& link) {
  const int rows = scan.range_m.rows, cols = scan.range_m.cols;
  if (scan.range_m.type() != CV_32FC1 || rows < 1 || cols < 1)
    throw Error("range scan: the range image must be CV_32FC1 with at least one row and column");
  if (scan.elevation_rad.size() != static_cast<std::size_t>(rows) || scan.azimuth_rad.size() != static_cast<std::size_t>(cols))
    throw Error("range scan: " + std::to_string(scan.elevation_rad.size()) + " elevations and " +
                std::to_string(scan.azimuth_rad.size()) + " azimuths for a " + std::to_string(rows) + " x " +
                std::to_string(cols) + " range image");
  const double step = evenAzimuthStep(scan);
  const int b = rangeBinColumns(scan);
  // A whole turn keeps whole bins (the few columns past the last one would overlap column 0's
  // azimuth); a partial sweep keeps its last, narrower bin.
  const bool whole_turn = cols * std::abs(step) >= 2.0 * M_PI - 0.5 * std::abs(step);
  const int bins = whole_turn ? std::max(1, cols / b) : (cols + b - 1) / b;
  SphericalGrid g;
  g.elevation_rad = scan.elevation_rad;
  g.azimuth_step_rad = step * b;
  g.azimuth_first_rad = scan.azimuth_rad[0] + step * 0.5 * (b - 1);  // the middle of the first bin
  g.columns = bins;
  g.ray = cv::Mat::zeros(rows, bins, CV_32FC3);
  cv::Mat range = cv::Mat::zeros(rows, bins, CV_32FC1);
  const float abs_m = static_cast<float>(link.discontinuity_abs_m), rel = static_cast<float>(link.discontinuity_rel);
  for (int r = 0; r < rows; ++r) {
    const float* in = scan.range_m.ptr<float>(r);
    for (int c = 0; c < bins; ++c) {
      const int c0 = c * b, c1 = std::min(cols, c0 + b);
      float nearest = std::numeric_limits<float>::infinity();
      for (int k = c0; k < c1; ++k)
        if (in[k] > 0.0f && std::isfinite(in[k])) nearest = std::min(nearest, in[k]);
      if (!std::isfinite(nearest)) continue;
      const float reach = abs_m + rel * nearest * nearest;
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      for (int k = c0; k < c1; ++k)
        if (in[k] > 0.0f && in[k] - nearest <= reach) sum += static_cast<double>(in[k]) * scan.direction(r, k);
      const double len = sum.norm();
      if (!(len > 0.0)) continue;
      // The mean point: its range along its own ray (the sum's length over the count would be
      // the same direction; only the length differs).
      int n = 0;
      for (int k = c0; k < c1; ++k) n += (in[k] > 0.0f && in[k] - nearest <= reach) ? 1 : 0;
      range.at<float>(r, c) = static_cast<float>(len / n);
      const Eigen::Vector3d u = sum / len;
      g.ray.at<cv::Vec3f>(r, c) = cv::Vec3f(static_cast<float>(u.x()), static_cast<float>(u.y()), static_cast<float>(u.z()));
    }
  }
  return {range, ViewProjection::spherical(std::move(g))};
}

DepthView makeRangeView(const RangeScan& scan, const SuperpixelParams& params) {
  auto [range, projection] = binRangeScan(scan, params.surfaces);
  return makeDepthView(range, projection, params);
}

SuperpixelParams lidarSuperpixelParams() {
  SuperpixelParams p;
  p.target_patch_area_m2 = 0.25;
  p.processing_step_px = 1;
  p.surfaces.discontinuity_abs_m = 0.1;
  p.surfaces.discontinuity_rel = 0.03;
  p.surfaces.normal_window_px_per_m = 0.1;
  p.surfaces.normal_min_radius_px = 1;
  p.surfaces.normal_max_radius_px = 2;
  p.surfaces.max_neighbour_normal_angle_deg = 15.0;
  p.surfaces.min_component_pixels = 6;
  p.kmeans.seed_sampling_step_px = 1;
  p.kmeans.kmeans_iteration_step_px = 1;
  p.kmeans.kmeans_coarse_iterations = 0;
  p.cleanup.min_patch_pixels = 3;
  return p;
}

PairParams lidarPairParams() {
  PairParams p;
  p.segment = lidarSuperpixelParams();
  const double k = std::sqrt(p.segment.target_patch_area_m2 / SuperpixelParams{}.target_patch_area_m2);
  // Centroid comparisons: with the patch radius.
  p.associate.feature_sets.ordering.e_r_m *= k;
  p.associate.match.r_dev_m *= k;
  auto& ransac = p.hypothesise.pose.ransac;
  ransac.inlier.distance_m *= k;
  ransac.edge_tolerance_m *= k;
  ransac.min_triangle_height_m *= k;
  p.hypothesise.guided.gates.max_distance_m *= k;
  for (double& gate : p.refine.dense.gates_m) gate *= k;
  p.refine.pixels.max_distance_m *= k;
  // Point comparisons: with the range noise.
  const double sigma = kLidarRangeSigmaM;
  for (auto* solver : {&p.hypothesise.pose.refinement, &p.refine.solver}) {
    solver->noise_sigma_m = sigma;
    solver->loss_scale_m = 2.5 * sigma;
  }
  p.certify.visibility.gate_m = 5.0 * sigma;
  p.certify.visibility.gate_per_m2 = 0.0;
  // Every cell.
  p.refine.pixels.pixel_step = 1;
  p.certify.visibility.pixel_step = 1;
  p.refine.edges.enabled = false;
  p.refine.slide_scan.enabled = false;
  return p;
}

}  // namespace gasp
