#include "gasp/pipeline/range_view.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <string>

#include <tbb/parallel_invoke.h>

#include <chrono>

#include "gasp/core/error.h"
#include "gasp/superpixels/depth_superpixels.h"

namespace gasp {

int rangeBinColumns(const RangeScan& scan) {
  validateLayout(scan, "range scan");
  return columnsPerRowPitch(scan);
}

std::pair<cv::Mat, ViewProjection> binRangeScan(const RangeScan& scan, const SuperpixelParams& params) {
  validateLayout(scan, "range scan");
  const int rows = scan.range_m.rows, cols = scan.range_m.cols;
  const double step = azimuthStep(scan);
  const int b = rangeBinColumns(scan);
  // A whole turn keeps whole bins, at most a turn of them (the columns past the last one would
  // overlap column 0's azimuth); a partial sweep keeps its last, narrower bin.
  const int bins = coversWholeTurn(scan)
                       ? std::max(1, std::min(cols / b, static_cast<int>(std::floor(2.0 * M_PI / (b * std::abs(step)) + 0.5))))
                       : (cols + b - 1) / b;
  SphericalGrid g;
  g.elevation_rad = scan.elevation_rad;
  g.azimuth_step_rad = step * b;
  g.azimuth_first_rad = scan.azimuth_rad[0] + step * 0.5 * (b - 1);  // the middle of the first bin
  g.columns = bins;
  g.ray = cv::Mat::zeros(rows, bins, CV_32FC3);
  cv::Mat range = cv::Mat::zeros(rows, bins, CV_32FC1);
  // A bin's returns on its nearest surface: within the range noise, plus what a surface seen at
  // up to max_incidence_deg spans across the bin (range x bin angle x tan(incidence)).
  const double spread = b * std::abs(step) * std::tan(params.max_incidence_deg * M_PI / 180.0);
  const double abs_m = params.surfaces.discontinuity_abs_m;
  for (int r = 0; r < rows; ++r) {
    const float* in = scan.range_m.ptr<float>(r);
    for (int c = 0; c < bins; ++c) {
      const int c0 = c * b, c1 = std::min(cols, c0 + b);
      float nearest = std::numeric_limits<float>::infinity();
      for (int k = c0; k < c1; ++k)
        if (in[k] > 0.0f && std::isfinite(in[k])) nearest = std::min(nearest, in[k]);
      if (!std::isfinite(nearest)) continue;
      const float reach = static_cast<float>(abs_m + spread * nearest);
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      int n = 0;
      for (int k = c0; k < c1; ++k)
        if (in[k] > 0.0f && in[k] - nearest <= reach) sum += static_cast<double>(in[k]) * scan.direction(r, k), ++n;
      const double len = sum.norm();
      if (!(len > 0.0)) continue;
      range.at<float>(r, c) = static_cast<float>(len / n);  // the mean point's range, on its own ray
      const Eigen::Vector3d u = sum / len;
      g.ray.at<cv::Vec3f>(r, c) = cv::Vec3f(static_cast<float>(u.x()), static_cast<float>(u.y()), static_cast<float>(u.z()));
    }
  }
  return {range, ViewProjection::spherical(std::move(g))};
}

DepthView makeRangeView(const RangeScan& scan, const SuperpixelParams& params, const ReturnsRefineParams& returns) {
  // Bad input is refused here, with one message, before the two halves run concurrently.
  validateLayout(scan, "range scan");
  validate(returns);
  // The binned cells' segmentation and the returns' normals need nothing of each other.
  DepthView view;
  std::shared_ptr<const SweepReturns> sweep;
  tbb::parallel_invoke(
      [&] {
        auto [range, projection] = binRangeScan(scan, params);
        view = makeDepthView(range, projection, params);
      },
      [&] { sweep = std::make_shared<const SweepReturns>(scan, returns); });
  view.returns = std::move(sweep);
  return view;
}

void validate(const LidarParams& p) {
  auto require = [](bool ok, const char* what) {
    if (!ok) throw Error(std::string("lidar parameters: ") + what);
  };
  require(p.patch_area_m2 > 0 && std::isfinite(p.patch_area_m2), "patch_area_m2 must be > 0 and finite");
  require(p.range_sigma_m > 0 && std::isfinite(p.range_sigma_m), "range_sigma_m must be > 0 and finite");
  require(p.violation_nats >= 0 && std::isfinite(p.violation_nats), "sweep_violation_nats must be >= 0 and finite");
  require(p.dense_sample_spacing_deg >= 0 && p.dense_sample_spacing_deg <= 90, "dense_sample_spacing_deg must be in [0, 90]");
  require(p.ground_search_max_offset_m > 0 && p.ground_search_max_offset_m <= 2.0 * GroundSearchParams{}.max_range_m,
          "ground_search_max_offset_m must be in (0, 80] m (twice the search's 40 m range)");
  require(p.sweep_speed_sigma_mps > 0 && std::isfinite(p.sweep_speed_sigma_mps) && p.sweep_rate_sigma_radps > 0 &&
              std::isfinite(p.sweep_rate_sigma_radps),
          "sweep_speed_sigma_mps and sweep_rate_sigma_radps must be > 0 and finite");
  validate(returnsRefineParams(p));
}

ReturnsRefineParams returnsRefineParams(const LidarParams& p) {
  ReturnsRefineParams r;
  r.gates_m = {15.0 * p.range_sigma_m, 7.5 * p.range_sigma_m, 4.0 * p.range_sigma_m};
  r.column_step = p.returns_column_step;
  r.look_up_columns = p.returns_look_up_columns;
  r.max_rounds = p.returns_max_rounds;
  r.converged_m = p.returns_converged_m;
  r.normal_half_width = p.returns_normal_half_width;
  r.max_flatness = p.returns_max_flatness;
  r.normal_noise_m = p.returns_normal_growth ? p.range_sigma_m : 0.0;
  r.basin_offset_m = 0.5 * r.gates_m[0];
  r.basin_tolerance_m = p.range_sigma_m;
  return r;
}

SuperpixelParams lidarSuperpixelParams(const LidarParams& lidar) {
  validate(lidar);
  SuperpixelParams p;
  p.target_patch_area_m2 = lidar.patch_area_m2;
  p.processing_step_px = 1;
  p.surfaces.discontinuity_abs_m = 5.0 * lidar.range_sigma_m;
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

double lidarCentroidScale(const LidarParams& lidar) {
  validate(lidar);
  return std::sqrt(lidar.patch_area_m2 / SuperpixelParams{}.target_patch_area_m2);
}

AssociationParams lidarAssociationParams(const AssociationParams& camera, const LidarParams& lidar) {
  const double k = lidarCentroidScale(lidar);
  AssociationParams out = camera;
  out.feature_sets.ordering.e_r_m *= k;
  out.match.r_dev_m *= k;
  return out;
}

PairParams lidarPairParams(const LidarParams& lidar) {
  const PairParams camera;
  return lidarPairParams(lidar, camera);
}

PairParams lidarPairParams(const LidarParams& lidar, const PairParams& camera) {
  PairParams p = camera;
  p.segment = lidarSuperpixelParams(lidar);
  const double k = lidarCentroidScale(lidar);
  // Centroid comparisons: with the patch radius.
  p.associate = lidarAssociationParams(p.associate, lidar);
  auto& ransac = p.hypothesise.pose.ransac;
  ransac.inlier.distance_m *= k;
  ransac.edge_tolerance_m *= k;
  ransac.min_triangle_height_m *= k;
  p.hypothesise.guided.gates.max_distance_m *= k;
  for (double& gate : p.refine.dense.gates_m) gate *= k;
  p.refine.pixels.max_distance_m *= k;
  // Point comparisons: with the range noise.
  const double sigma = lidar.range_sigma_m;
  for (auto* solver : {&p.hypothesise.pose.refinement, &p.refine.solver}) {
    solver->noise_sigma_m = sigma;
    solver->loss_scale_m = 2.5 * sigma;
  }
  p.certify.visibility.gate_m = 5.0 * sigma;
  p.certify.visibility.gate_per_m2 = 0.0;
  // A binned cell is 0.4-2 deg wide: gates widen by its spread on the surface.
  p.certify.visibility.pixel_spread = true;
  p.refine.pixels.pixel_footprint = true;
  // Every cell, or as far apart as a camera's samples where the cells are finer.
  p.refine.pixels.pixel_step = 1;
  p.refine.pixels.sample_spacing_deg = lidar.dense_sample_spacing_deg;
  p.certify.visibility.pixel_step = 1;
  p.refine.edges.enabled = false;
  p.refine.slide_scan.enabled = false;
  p.certify.symmetry_test = lidar.symmetry_test;
  p.certify.violation_nats = lidar.violation_nats;
  p.returns = returnsRefineParams(lidar);
  p.ground_search.enabled = lidar.ground_search;
  p.ground_search.max_offset_m = lidar.ground_search_max_offset_m;
  p.sweep_motion.enabled = lidar.sweep_motion;
  p.sweep_motion.speed_sigma_mps = lidar.sweep_speed_sigma_mps;
  p.sweep_motion.rate_sigma_radps = lidar.sweep_rate_sigma_radps;
  return p;
}

RangePairResult registerRangeScans(const RangeScan& source, const RangeScan& target, const PairParams& params) {
  validate(params);
  RangePairResult out;
  const auto t0 = std::chrono::steady_clock::now();
  DepthView a, b;  // one TBB task each, as makeDepthViews()
  tbb::parallel_invoke([&] { a = makeRangeView(source, params.segment, params.returns); },
                       [&] { b = makeRangeView(target, params.segment, params.returns); });
  out.segmentation_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  out.pair = registerViews(a, b, params);
  return out;
}

RangePairResult registerRangeScans(const RangeScan& source, const RangeScan& target, const LidarParams& lidar) {
  return registerRangeScans(source, target, lidarPairParams(lidar));
}

}  // namespace gasp
