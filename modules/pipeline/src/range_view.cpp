#include "gasp/pipeline/range_view.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include <Eigen/Eigenvalues>
#include <tbb/parallel_invoke.h>

#include <chrono>

#include "gasp/core/error.h"
#include "gasp/pipeline/model_error.h"
#include "gasp/superpixels/depth_superpixels.h"

namespace gasp {

int rangeBinColumns(const RangeScan& scan) {
  validateLayout(scan, "range scan");
  return std::max(1, static_cast<int>(std::lround(rowPitch(scan) / std::abs(azimuthStep(scan)))));
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

DepthView makeRangeView(const RangeScan& scan, const SuperpixelParams& params) {
  auto [range, projection] = binRangeScan(scan, params);
  return makeDepthView(range, projection, params);
}

void validate(const LidarParams& p) {
  auto require = [](bool ok, const char* what) {
    if (!ok) throw Error(std::string("lidar parameters: ") + what);
  };
  require(p.patch_area_m2 > 0 && std::isfinite(p.patch_area_m2), "patch_area_m2 must be > 0 and finite");
  require(p.range_sigma_m > 0 && std::isfinite(p.range_sigma_m), "range_sigma_m must be > 0 and finite");
  validate(returnsRefineParams(p));
}

void validate(const ReturnsRefineParams& r) {
  auto require = [](bool ok, const char* what) {
    if (!ok) throw Error(std::string("lidar parameters: ") + what);
  };
  require(!r.gates_m.empty(), "the returns' gates must not be empty");
  for (const double g : r.gates_m) require(g > 0 && std::isfinite(g), "the returns' gates must be > 0 and finite");
  require(r.column_step >= 1 && r.max_rounds >= 1 && r.max_rounds <= 1000,
          "returns_column_step must be >= 1 and returns_max_rounds in [1, 1000]");
  require(r.look_up_columns >= 0 && r.look_up_columns <= 100, "returns_look_up_columns must be in [0, 100]");
  require(r.converged_m >= 0 && std::isfinite(r.converged_m), "returns_converged_m must be >= 0 and finite");
  require(r.normal_half_width >= 1 && r.normal_half_width <= 100 && r.max_flatness > 0 && r.max_flatness <= 1,
          "returns_normal_half_width must be in [1, 100] and returns_max_flatness in (0, 1]");
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

PairParams lidarPairParams(const LidarParams& lidar) {
  PairParams p;
  p.segment = lidarSuperpixelParams(lidar);
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
  // Every cell.
  p.refine.pixels.pixel_step = 1;
  p.certify.visibility.pixel_step = 1;
  p.refine.edges.enabled = false;
  p.refine.slide_scan.enabled = false;
  return p;
}

namespace {

double msSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

/// A sweep's returns as points with normals, and the look-up of the return a point falls on.
class ReturnSurface {
 public:
  /// `scan` passed validateLayout().
  ReturnSurface(const RangeScan& scan, const ReturnsRefineParams& p)
      : scan_(scan), rows_(scan.range_m.rows), cols_(scan.range_m.cols), whole_turn_(coversWholeTurn(scan)) {
    half_cell_rad_ = 0.5 * std::hypot(rowPitch(scan), azimuthStep(scan));
    const double nan = std::numeric_limits<double>::quiet_NaN();
    point_.assign(static_cast<std::size_t>(rows_) * cols_, Eigen::Vector3d::Constant(nan));
    normal_.assign(point_.size(), Eigen::Vector3d::Zero());
    for (int r = 0; r < rows_; ++r)
      for (int c = 0; c < cols_; ++c)
        if (const float d = scan.range_m.at<float>(r, c); d > 0.0f && std::isfinite(d))
          point_[index(r, c)] = static_cast<double>(d) * scan.direction(r, c);
    for (int r = 0; r < rows_; ++r)
      for (int c = 0; c < cols_; ++c) normal_[index(r, c)] = fitNormal(r, c, p);
  }

  /// The return with a normal nearest in direction to `q` (sensor frame): in the row of the
  /// nearest elevation, the nearest column within `reach` columns (a sweep may leave every other
  /// column empty, a dual-return VLP-16's does; across the seam of a whole turn). Its cell index,
  /// or -1.
  int lookUp(const Eigen::Vector3d& q, int reach) const {
    int row = 0, nearest = 0;
    if (!nearestCell(scan_, q, row, nearest)) return -1;
    for (int k = 0; k <= reach; ++k)
      for (const int side : {-1, 1}) {
        int col = nearest + side * k;
        if (whole_turn_) col = ((col % cols_) + cols_) % cols_;
        if (col < 0 || col >= cols_) continue;
        const std::size_t i = index(row, col);
        if (!normal_[i].isZero()) return static_cast<int>(i);
        if (k == 0) break;
      }
    return -1;
  }
  const Eigen::Vector3d& point(int i) const { return point_[static_cast<std::size_t>(i)]; }
  const Eigen::Vector3d& normal(int i) const { return normal_[static_cast<std::size_t>(i)]; }
  double halfCellRad() const { return half_cell_rad_; }

 private:
  std::size_t index(int r, int c) const { return static_cast<std::size_t>(r) * cols_ + c; }

  /// The plane of the returns around (r, c) on the same surface (ranges within 5 % + 0.1 m of the
  /// centre's), over at least two rows; zero when there is none or it is not flat.
  Eigen::Vector3d fitNormal(int r, int c, const ReturnsRefineParams& p) const {
    const Eigen::Vector3d& centre = point_[index(r, c)];
    if (!centre.allFinite()) return Eigen::Vector3d::Zero();
    const double range = centre.norm(), reach = 0.1 + 0.05 * range;
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    Eigen::Matrix3d outer = Eigen::Matrix3d::Zero();
    int n = 0, rows_used = 0;
    for (int rr = std::max(0, r - 1); rr <= std::min(rows_ - 1, r + 1); ++rr) {
      bool used = false;
      for (int cc = std::max(0, c - p.normal_half_width); cc <= std::min(cols_ - 1, c + p.normal_half_width); ++cc) {
        const Eigen::Vector3d& q = point_[index(rr, cc)];
        if (!q.allFinite() || std::abs(q.norm() - range) > reach) continue;
        sum += q, outer += q * q.transpose(), ++n, used = true;
      }
      rows_used += used ? 1 : 0;
    }
    if (n < 5 || rows_used < 2) return Eigen::Vector3d::Zero();
    const Eigen::Vector3d mean = sum / n;
    const Eigen::Matrix3d cov = outer / n - mean * mean.transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
    const Eigen::Vector3d lambda = eig.eigenvalues().cwiseMax(0.0);
    if (!(lambda(1) > 0.0) || std::sqrt(lambda(0) / lambda(1)) > p.max_flatness) return Eigen::Vector3d::Zero();
    Eigen::Vector3d normal = eig.eigenvectors().col(0);
    return normal.dot(centre) > 0.0 ? -normal : normal;
  }

  const RangeScan& scan_;
  int rows_ = 0, cols_ = 0;
  bool whole_turn_ = false;
  double half_cell_rad_ = 0.0;
  std::vector<Eigen::Vector3d> point_, normal_;
};

}  // namespace

RegistrationResult refineOnReturns(const RangeScan& source, const RangeScan& target, const Isometry3& T_target_source,
                                   const ReturnsRefineParams& p, const RefinementParams& solver, double max_incidence_deg) {
  RegistrationResult result;
  result.T_target_source = T_target_source;
  validate(p);
  if (!(max_incidence_deg > 0.0 && max_incidence_deg < 90.0))
    throw Error("returns refinement: max_incidence_deg must be in (0, 90)");
  validateLayout(source, "returns refinement: the source sweep");
  validateLayout(target, "returns refinement: the target sweep");
  const ReturnSurface surface(target, p);
  std::vector<Eigen::Vector3d> points;
  for (int r = 0; r < source.range_m.rows; ++r)
    for (int c = 0; c < source.range_m.cols; c += p.column_step)
      if (const float d = source.range_m.at<float>(r, c); d > 0.0f && std::isfinite(d))
        points.push_back(static_cast<double>(d) * source.direction(r, c));
  const double min_cos = std::cos(max_incidence_deg * M_PI / 180.0);
  Isometry3 T = T_target_source;
  for (int round = 0; round < p.max_rounds; ++round) {
    const double gate = p.gates_m[std::min(static_cast<std::size_t>(round), p.gates_m.size() - 1)];
    std::vector<PointToPlane> terms;
    for (const Eigen::Vector3d& ps : points) {
      const Eigen::Vector3d pt = T * ps;
      const int i = surface.lookUp(pt, p.look_up_columns);
      if (i < 0) continue;
      const Eigen::Vector3d& n = surface.normal(i);
      const Eigen::Vector3d& q = surface.point(i);
      const double range = q.norm();
      const double cos_i = std::abs(n.dot(q)) / range;
      if (cos_i < min_cos || std::abs(n.dot(pt - q)) > gate) continue;
      // In the plane, the point can be a cell's footprint away from the return it fell on.
      if ((pt - q).norm() > gate + range * surface.halfCellRad() / cos_i) continue;
      terms.push_back(PointToPlane{ps, q, n, 1.0});
    }
    if (terms.size() < 6) {
      result.reason = "returns refinement: " + std::to_string(terms.size()) + " point-to-plane terms in round " +
                      std::to_string(round + 1) + " (at least 6 needed)";
      result.success = false;
      return result;
    }
    RegistrationResult next = refinePose({}, T, solver, terms);
    if (!next.success) {  // a failed or degenerate solve: its free directions would drift on
      result.reason = "returns refinement: " + next.reason;
      result.success = false;
      return result;
    }
    double moved2 = 0.0;
    for (const Eigen::Vector3d& ps : points) moved2 += (next.T_target_source * ps - T * ps).squaredNorm();
    T = next.T_target_source;
    result = next;
    const bool last_gate = round + 1 >= static_cast<int>(p.gates_m.size());
    if (last_gate && std::sqrt(moved2 / static_cast<double>(points.size())) < p.converged_m) break;
  }
  return result;
}

RangePairResult registerRangeScans(const RangeScan& source, const RangeScan& target, const PairParams& params,
                                   const ReturnsRefineParams& returns) {
  RangePairResult out;
  auto t0 = std::chrono::steady_clock::now();
  DepthView a, b;  // one TBB task each, as makeDepthViews()
  tbb::parallel_invoke([&] { a = makeRangeView(source, params.segment); }, [&] { b = makeRangeView(target, params.segment); });
  out.segmentation_ms = msSince(t0);
  out.pair = registerViews(a, b, params);
  if (!out.pair.pose.success) return out;
  t0 = std::chrono::steady_clock::now();
  const RegistrationResult refined = refineOnReturns(source, target, out.pair.pose.T_target_source, returns,
                                                     params.refine.solver, params.segment.max_incidence_deg);
  out.returns_ms = msSince(t0);
  if (!refined.success) {
    out.returns_reason = refined.reason;
    return out;
  }
  out.returns_refined = true;
  out.pair.pose.T_target_source = refined.T_target_source;
  out.pair.pose.information = refined.information;
  out.pair.pose.information_eigenvalues = refined.information_eigenvalues;
  out.pair.edge_information = informationWithModelError(refined.information, params.certify.model_error);
  return out;
}

RangePairResult registerRangeScans(const RangeScan& source, const RangeScan& target, const LidarParams& lidar) {
  return registerRangeScans(source, target, lidarPairParams(lidar), returnsRefineParams(lidar));
}

}  // namespace gasp
