#include "gasp/pipeline/returns_stage.h"

#include <Eigen/Eigenvalues>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "gasp/core/error.h"
#include "free_space_verdict.h"
#include "return_term.h"

namespace gasp {

void validate(const ReturnsRefineParams& r) {
  auto require = [](bool ok, const char* what) {
    if (!ok) throw Error(std::string("lidar parameters: ") + what);
  };
  for (const double g : r.gates_m) require(g > 0 && std::isfinite(g), "the returns' gates must be > 0 and finite");
  require(r.column_step >= 1 && r.return_step >= 1 && r.max_rounds >= 1 && r.max_rounds <= 1000,
          "returns_column_step and the return step must be >= 1 and returns_max_rounds in [1, 1000]");
  require(r.look_up_columns >= 0 && r.look_up_columns <= 100, "returns_look_up_columns must be in [0, 100]");
  require(r.converged_m >= 0 && std::isfinite(r.converged_m), "returns_converged_m must be >= 0 and finite");
  require(r.normal_half_width >= 0 && r.normal_half_width <= 100 && r.max_flatness > 0 && r.max_flatness <= 1,
          "returns_normal_half_width must be in [0, 100] (0: square in view angle) and returns_max_flatness in (0, 1]");
  require(r.normal_noise_m >= 0 && std::isfinite(r.normal_noise_m), "the returns' normal noise must be >= 0 and finite (0: adjacent rows only)");
  require(r.basin_offset_m > 0 && std::isfinite(r.basin_offset_m) && r.basin_tolerance_m > 0 &&
              r.basin_tolerance_m < r.basin_offset_m,
          "the returns' basin tolerance must be > 0 and below their offset (a restart that did not move would pass)");
}

int squareNormalHalfWidth(const RangeScan& scan) {
  validateLayout(scan, "sweep returns");
  return std::min(columnsPerRowPitch(scan), 100);
}

SweepReturns::SweepReturns(const RangeScan& scan, const ReturnsRefineParams& p)
    : scan_(scan),
      normal_half_width_(p.normal_half_width),
      max_flatness_(p.max_flatness),
      normal_noise_m_(p.normal_noise_m),
      plane_tolerance_(p.gates_m.back()) {
  validate(p);
  validateLayout(scan_, "sweep returns");
  if (normal_half_width_ == 0) normal_half_width_ = squareNormalHalfWidth(scan_);
  row_pitch_rad_ = rowPitch(scan_);
  max_row_spacing_ = std::max(1, scan_.range_m.rows / 8);
  // Its own copy of the images: a driver may reuse its buffers for the next sweep.
  scan_.range_m = scan.range_m.clone();
  if (!scan.ray.empty()) scan_.ray = scan.ray.clone();
  rows_ = scan_.range_m.rows;
  cols_ = scan_.range_m.cols;
  whole_turn_ = coversWholeTurn(scan_);
  half_cell_rad_ = 0.5 * std::hypot(row_pitch_rad_, azimuthStep(scan_));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  point_.assign(static_cast<std::size_t>(rows_) * static_cast<std::size_t>(cols_), Eigen::Vector3d::Constant(nan));
  normal_.assign(point_.size(), Eigen::Vector3d::Zero());
  for (int r = 0; r < rows_; ++r)
    for (int c = 0; c < cols_; ++c)
      if (const float d = scan_.range_m.at<float>(r, c); d > 0.0f && std::isfinite(d))
        point_[index(r, c)] = static_cast<double>(d) * scan_.direction(r, c);
  // Each row's running sums of the returns' moments, so a window's sums are two look-ups where
  // every return in it lies on the centre's surface (the common case on a wide window).
  std::vector<Moments> prefix(static_cast<std::size_t>(rows_) * static_cast<std::size_t>(cols_ + 1));
  for (int r = 0; r < rows_; ++r) {
    Moments* row = &prefix[static_cast<std::size_t>(r) * static_cast<std::size_t>(cols_ + 1)];
    for (int c = 0; c < cols_; ++c) {
      row[c + 1] = row[c];
      if (const Eigen::Vector3d& q = point_[index(r, c)]; q.allFinite()) row[c + 1].add(q);
    }
  }
  tbb::parallel_for(0, rows_, [&](int r) {
    for (int c = 0; c < cols_; ++c) normal_[index(r, c)] = fitNormal(r, c, prefix);
  });
}

int SweepReturns::windowRowSpacing(double range) const {
  if (!(normal_noise_m_ > 0.0) || !(range > 0.0)) return 1;
  // The spread the rows must reach, in row pitches at this range; three rows k apart spread
  // k sqrt(2 / 3) pitches.
  const double need = normal_noise_m_ / (max_flatness_ * range * row_pitch_rad_);
  const double k = std::ceil(need / std::sqrt(2.0 / 3.0) - 1e-9);
  return k >= static_cast<double>(max_row_spacing_) ? max_row_spacing_ : std::max(1, static_cast<int>(k));
}

int SweepReturns::lookUp(const Eigen::Vector3d& q, int reach) const {
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

Eigen::Vector3d SweepReturns::surfaceNear(int i, const Eigen::Vector3d& q, double tolerance) const {
  const int r = i / cols_, c = i % cols_;
  const Eigen::Vector3d& p0 = point_[static_cast<std::size_t>(i)];
  const Eigen::Vector3d& n = normal_[static_cast<std::size_t>(i)];
  // The weights come from the directions alone (the returns' rays carry no range noise), so
  // they do not depend on the noise of the offsets they weigh: a direction's gnomonic offset
  // from return i's on the plane tangent to the sphere there (all scaled by 1 / |p0|^2, which
  // leaves the weights as they are).
  const double inv_p0 = 1.0 / p0.squaredNorm();
  const auto gnomonic = [&](const Eigen::Vector3d& p) -> Eigen::Vector3d { return p / p.dot(p0) - inv_p0 * p0; };
  const Eigen::Vector3d g = gnomonic(q);
  // Return i's neighbour toward q along one axis that lies on its plane: its offset from return
  // i and its direction's gnomonic offset; zeros where there is none.
  const auto toward = [&](int r1, int c1, int r2, int c2) -> std::pair<Eigen::Vector3d, Eigen::Vector3d> {
    std::pair<Eigen::Vector3d, Eigen::Vector3d> best{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
    double best_along = 0.0;
    for (const auto& [rr, cc0] : {std::pair{r1, c1}, std::pair{r2, c2}}) {
      int cc = cc0;
      if (whole_turn_) cc = ((cc % cols_) + cols_) % cols_;
      if (rr < 0 || rr >= rows_ || cc < 0 || cc >= cols_) continue;
      const Eigen::Vector3d& p = point_[index(rr, cc)];
      if (!p.allFinite() || !(p.dot(p0) > 0.0)) continue;
      const Eigen::Vector3d e = p - p0, ge = gnomonic(p);
      const double along = g.dot(ge) / ge.squaredNorm();
      if (std::abs(n.dot(e)) <= tolerance && along > best_along) best = {e, ge}, best_along = along;
    }
    return best;
  };
  const auto [across, g_across] = toward(r - 1, c, r + 1, c);
  const auto [along, g_along] = toward(r, c - 1, r, c + 1);
  const bool has_across = !g_across.isZero(), has_along = !g_along.isZero();
  if (has_across && has_along) {
    // The least-squares weights of g on the two directions (the 2 x 2 normal equations).
    const double aa = g_across.squaredNorm(), bb = g_along.squaredNorm(), ab = g_across.dot(g_along);
    const double det = aa * bb - ab * ab;
    if (det > 1e-6 * aa * bb) {
      const double ga = g.dot(g_across), gb = g.dot(g_along);
      const double wa = std::clamp((bb * ga - ab * gb) / det, 0.0, 1.0), wb = std::clamp((aa * gb - ab * ga) / det, 0.0, 1.0);
      return p0 + wa * across + wb * along;
    }
  }
  if (has_across) return p0 + std::clamp(g.dot(g_across) / g_across.squaredNorm(), 0.0, 1.0) * across;
  if (has_along) return p0 + std::clamp(g.dot(g_along) / g_along.squaredNorm(), 0.0, 1.0) * along;
  return p0;
}

namespace {

/// How far in range a return may lie from another's and be on its surface [m]: 0.1 m + 5 %.
float sameSurfaceReach(float range) { return 0.1f + 0.05f * range; }

}  // namespace

bool SweepReturns::addRow(int row, int lo, int hi, float range, const std::vector<Moments>& prefix, Moments& m) const {
  const float reach = sameSurfaceReach(range);
  const float* ranges = scan_.range_m.ptr<float>(row);
  bool all_on_surface = true;
  for (int cc = lo; cc <= hi && all_on_surface; ++cc)
    all_on_surface = !point_[index(row, cc)].allFinite() || std::abs(ranges[cc] - range) <= reach;
  const double before = m.n;
  if (all_on_surface) {
    const Moments* sums = &prefix[static_cast<std::size_t>(row) * static_cast<std::size_t>(cols_ + 1)];
    m.addDifference(sums[hi + 1], sums[lo]);
  } else {
    for (int cc = lo; cc <= hi; ++cc)
      if (const Eigen::Vector3d& q = point_[index(row, cc)]; q.allFinite() && std::abs(ranges[cc] - range) <= reach) m.add(q);
  }
  return m.n > before;
}

/// The plane of the returns around (r, c) on the same surface, over at least two rows; zero when
/// there is none or it is not flat. `prefix`: each row's running sums of its returns' moments
/// (cols + 1 per row).
/// - The same surface is first the returns whose ranges lie within 5 % + 0.1 m of the centre's.
/// - Where those of three adjacent rows are not flat and spread too little across the beam for a
///   plane measured with the range noise to pass (windowRowSpacing() > 1), three rows that far
///   apart over as many times the columns (ReturnsRefineParams::normal_noise_m).
/// - Where no other row's do (a surface seen at grazing incidence across the rows, as the ground
///   is: a VLP-16's rings on it lie metres apart in range), each of the three rows nearest r (r's
///   own and the two beside it, or the two inside it at the first and last row) contributes the
///   returns on its own centre column's surface (within the same reach of that return's range),
///   and the plane of the three is kept only when every one of them lies within plane_tolerance_
///   of it along its own ray (where the range noise is): three rows on one plane, not a row of
///   the ground under a row of a facade or a car.
Eigen::Vector3d SweepReturns::fitNormal(int r, int c, const std::vector<Moments>& prefix) const {
  const Eigen::Vector3d& centre = point_[index(r, c)];
  if (!centre.allFinite()) return Eigen::Vector3d::Zero();
  const float range = scan_.range_m.at<float>(r, c);
  const int lo = std::max(0, c - normal_half_width_), hi = std::min(cols_ - 1, c + normal_half_width_);
  const auto flatNormal = [&](const Moments& m, Eigen::Vector3d& mean) -> Eigen::Vector3d {
    mean = m.s / m.n;
    const Eigen::Matrix3d cov = m.ss / m.n - mean * mean.transpose();
    // The closed form of a 3 x 3 solve: the smallest eigenvalue is far from the others wherever
    // the flatness test can pass, where it is as accurate as the iterative solve.
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
    eig.computeDirect(cov);
    const Eigen::Vector3d lambda = eig.eigenvalues().cwiseMax(0.0);
    if (!(lambda(1) > 0.0) || std::sqrt(lambda(0) / lambda(1)) > max_flatness_) return Eigen::Vector3d::Zero();
    const Eigen::Vector3d normal = eig.eigenvectors().col(0);
    return normal.dot(centre) > 0.0 ? -normal : normal;
  };
  // Whether row rr's returns in [first_col, last_col] on the surface of a return at range `own`
  // all lie on the plane (normal, through mean) within the last gate along their rays.
  const auto rowOnPlane = [&](int rr, int first_col, int last_col, float own, const Eigen::Vector3d& normal,
                              const Eigen::Vector3d& mean) {
    const float reach = sameSurfaceReach(own);
    const float* ranges = scan_.range_m.ptr<float>(rr);
    for (int cc = first_col; cc <= last_col; ++cc)
      if (const Eigen::Vector3d& q = point_[index(rr, cc)];
          q.allFinite() && std::abs(ranges[cc] - own) <= reach &&
          std::abs(normal.dot(q - mean)) * static_cast<double>(ranges[cc]) > plane_tolerance_ * std::abs(normal.dot(q)))
        return false;
    return true;
  };
  Moments m;
  int rows_used = 0;
  for (int rr = std::max(0, r - 1); rr <= std::min(rows_ - 1, r + 1); ++rr) rows_used += addRow(rr, lo, hi, range, prefix, m) ? 1 : 0;
  Eigen::Vector3d mean;
  if (rows_used >= 2) {
    if (m.n >= 5)
      if (const Eigen::Vector3d normal = flatNormal(m, mean); !normal.isZero()) return normal;
    const int k = windowRowSpacing(static_cast<double>(range));
    if (k == 1) return Eigen::Vector3d::Zero();
    // Three adjacent rows failed where the noise asks for more: three rows k apart, r's own
    // among them (r and the two beyond it within k of the first and last rows), each over k
    // times the columns. k <= rows / 8 leaves room for them.
    const int grown_lo = std::max(0, c - k * normal_half_width_), grown_hi = std::min(cols_ - 1, c + k * normal_half_width_);
    const int first_row = r - k < 0 ? r : (r + k > rows_ - 1 ? r - 2 * k : r - k);
    const std::array<int, 3> grown_rows = {first_row, first_row + k, first_row + 2 * k};
    Moments g;
    int grown_used = 0;
    for (const int rr : grown_rows) grown_used += addRow(rr, grown_lo, grown_hi, range, prefix, g) ? 1 : 0;
    if (grown_used < 2 || g.n < 5) return Eigen::Vector3d::Zero();
    const Eigen::Vector3d normal = flatNormal(g, mean);
    if (normal.isZero()) return normal;
    // A grown window can hold a corner's other surface as a minority that the flatness test
    // lets through with a tilted plane: every return in it must lie on the plane, within the
    // last gate along its ray, as the ground's three rows must below.
    for (const int rr : grown_rows)
      if (!rowOnPlane(rr, grown_lo, grown_hi, range, normal, mean)) return Eigen::Vector3d::Zero();
    return normal;
  }
  if (rows_ < 3) return Eigen::Vector3d::Zero();
  const int first = std::clamp(r - 1, 0, rows_ - 3);  // the three rows nearest r (r's own at the ends)
  Moments rows3;
  for (int rr = first; rr <= first + 2; ++rr) {
    const float own = scan_.range_m.at<float>(rr, c);
    const double before = rows3.n;
    if (!point_[index(rr, c)].allFinite() || !addRow(rr, lo, hi, own, prefix, rows3) || rows3.n - before < 2.0)
      return Eigen::Vector3d::Zero();  // each row a segment, not a single return
  }
  const Eigen::Vector3d normal = flatNormal(rows3, mean);
  if (normal.isZero()) return normal;
  for (int rr = first; rr <= first + 2; ++rr)
    if (!rowOnPlane(rr, lo, hi, scan_.range_m.at<float>(rr, c), normal, mean)) return Eigen::Vector3d::Zero();
  return normal;
}

int returnTerm(const Eigen::Vector3d& pt, const SweepReturns& target, double gate, int look_up_columns, double min_cos,
               Eigen::Vector3d& plane_point, Eigen::Vector3d& normal) {
  const int i = target.lookUp(pt, look_up_columns);
  if (i < 0) return -1;
  const Eigen::Vector3d& n = target.normal(i);
  const Eigen::Vector3d& q = target.point(i);
  const double range = q.norm();
  const double cos_i = std::abs(n.dot(q)) / range;
  // In the plane, the point can be a cell's footprint away from the return it fell on.
  if (cos_i < min_cos || (pt - q).norm() > gate + range * target.halfCellRad() / cos_i) return -1;
  const Eigen::Vector3d x = target.surfaceNear(i, pt, target.planeTolerance());
  if (std::abs(n.dot(pt - x)) > gate) return -1;
  plane_point = x;
  normal = n;
  return i;
}

std::vector<PointToPlane> returnTerms(const std::vector<Eigen::Vector3d>& source_points, const SweepReturns& target,
                                      const Isometry3& T_target_source, double gate, int look_up_columns,
                                      double max_incidence_deg) {
  const double min_cos = std::cos(max_incidence_deg * M_PI / 180.0);
  const auto termsOf = [&](std::size_t begin, std::size_t end, std::vector<PointToPlane>& terms) {
    Eigen::Vector3d x, n;
    for (std::size_t k = begin; k < end; ++k) {
      const Eigen::Vector3d& ps = source_points[k];
      if (returnTerm(T_target_source * ps, target, gate, look_up_columns, min_cos, x, n) >= 0)
        terms.push_back(PointToPlane{ps, x, n, 1.0});
    }
  };
  // Blocks of points looked up concurrently, their terms joined in the points' order.
  constexpr std::size_t kPointsPerTask = 2048;
  const std::size_t blocks = (source_points.size() + kPointsPerTask - 1) / kPointsPerTask;
  std::vector<std::vector<PointToPlane>> per_block(blocks);
  tbb::parallel_for(std::size_t{0}, blocks, [&](std::size_t b) {
    termsOf(b * kPointsPerTask, std::min(source_points.size(), (b + 1) * kPointsPerTask), per_block[b]);
  });
  std::vector<PointToPlane> terms;
  std::size_t total = 0;
  for (const auto& block : per_block) total += block.size();
  terms.reserve(total);
  for (const auto& block : per_block) terms.insert(terms.end(), block.begin(), block.end());
  return terms;
}

RegistrationResult refineOnReturns(const SweepReturns& source, const SweepReturns& target, const Isometry3& T_target_source,
                                   const ReturnsRefineParams& p, const RefinementParams& solver, double max_incidence_deg) {
  RegistrationResult result;
  result.T_target_source = T_target_source;
  validate(p);
  if (!(max_incidence_deg > 0.0 && max_incidence_deg < 90.0))
    throw Error("returns refinement: max_incidence_deg must be in (0, 90)");
  std::vector<Eigen::Vector3d> points;
  long valid = 0;
  for (int r = 0; r < source.rows(); ++r)
    for (int c = 0; c < source.cols(); c += p.column_step)
      if (const Eigen::Vector3d& q = source.point(r, c); q.allFinite() && valid++ % p.return_step == 0)
        points.push_back(q);
  Isometry3 T = T_target_source;
  for (int round = 0; round < p.max_rounds; ++round) {
    const double gate = p.gates_m[std::min(static_cast<std::size_t>(round), p.gates_m.size() - 1)];
    const std::vector<PointToPlane> terms = returnTerms(points, target, T, gate, p.look_up_columns, max_incidence_deg);
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

RegistrationResult refineOnReturns(const RangeScan& source, const RangeScan& target, const Isometry3& T_target_source,
                                   const ReturnsRefineParams& params, const RefinementParams& solver,
                                   double max_incidence_deg) {
  validate(params);
  return refineOnReturns(SweepReturns(source, params), SweepReturns(target, params), T_target_source, params, solver,
                         max_incidence_deg);
}

std::optional<Eigen::Vector3d> weakestTranslation(const Matrix6d& information) {
  const Eigen::LDLT<Matrix6d> ldlt(information);
  if (!information.allFinite() || ldlt.info() != Eigen::Success || !ldlt.isPositive()) return std::nullopt;
  const Matrix6d covariance = ldlt.solve(Matrix6d::Identity());
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(covariance.topLeftCorner<3, 3>());
  return Eigen::Vector3d(eig.eigenvectors().col(2));
}

ReturnsBasin returnsBasin(const SweepReturns& source, const SweepReturns& target, const RegistrationResult& pose,
                          const ReturnsRefineParams& params, const RefinementParams& solver, double max_incidence_deg) {
  validate(params);
  ReturnsBasin b;
  const std::optional<Eigen::Vector3d> weakest = weakestTranslation(pose.information);
  if (!pose.T_target_source.matrix().allFinite() || !weakest) {
    b.reason = "the returns' basin: no finite pose with a positive definite information";
    return b;
  }
  b.direction = *weakest;
  std::array<double, 2> end_m{};
  tbb::parallel_for(0, 2, [&](int k) {
    const double offset = k == 0 ? -params.basin_offset_m : params.basin_offset_m;
    const Isometry3 start = Eigen::Translation3d(offset * b.direction) * pose.T_target_source;
    RegistrationResult& q = b.ends[static_cast<std::size_t>(k)];
    q = refineOnReturns(source, target, start, params, solver, max_incidence_deg);
    end_m[static_cast<std::size_t>(k)] = q.success ? (q.T_target_source.translation() - pose.T_target_source.translation()).norm()
                                                   : std::numeric_limits<double>::infinity();
  });
  b.farthest_m = std::max(end_m[0], end_m[1]);
  b.held = b.farthest_m <= params.basin_tolerance_m;
  if (!b.held && !std::isfinite(b.farthest_m)) {
    char text[200];
    std::snprintf(text, sizeof text, "the returns' rounds restarted %.2f m from their pose along (%.2f, %.2f, %.2f) failed",
                  params.basin_offset_m, b.direction.x(), b.direction.y(), b.direction.z());
    b.reason = text;
  } else if (!b.held) {
    char text[240];
    std::snprintf(text, sizeof text,
                  "the returns' rounds do not fix the translation along (%.2f, %.2f, %.2f): restarted %.2f m either side, "
                  "one ends %.1f cm from their pose (at most %.1f cm)",
                  b.direction.x(), b.direction.y(), b.direction.z(), params.basin_offset_m, 100.0 * b.farthest_m,
                  100.0 * params.basin_tolerance_m);
    b.reason = text;
  }
  return b;
}

namespace {

/// landOnReturns() with the incidence's clamp as its tangent (computed once by a caller's loop).
ReturnLanding land(const SweepReturns& sweep, const Eigen::Vector3d& q, double range_sigma_m, double max_tan) {
  ReturnLanding l;
  const int i = sweep.lookUp(q, 0);
  if (i < 0) return l;
  const Eigen::Vector3d& t = sweep.point(i);
  const Eigen::Vector3d& n = sweep.normal(i);
  const double range = t.norm(), cos_i = std::abs(n.dot(t)) / range;
  const double tan_i = std::min(max_tan, std::sqrt(std::max(0.0, 1.0 - cos_i * cos_i)) / std::max(cos_i, 1e-9));
  l.index = i;
  l.gate_m = 5.0 * range_sigma_m + range * sweep.halfCellRad() * tan_i;
  // Against the plane a term would use (the return's normal through the surface between the
  // returns around q): on the ground a VLP-16's rings lie metres apart in range, and the nearest
  // ring's range is not the surface's at q. How far q lies beyond it along q's own ray: the
  // plane's distance over the ray's cosine with it, the incidence clamped as the gate's.
  const Eigen::Vector3d x = sweep.surfaceNear(i, q, sweep.planeTolerance());
  l.plane_m = n.dot(q - x);
  const double q_range = q.norm(), cos_q = n.dot(q) / q_range;  // negative: n faces the sensor
  const double min_cos = 1.0 / std::sqrt(1.0 + max_tan * max_tan);
  l.beyond_m = l.plane_m / (cos_q < -min_cos ? cos_q : -min_cos);
  return l;
}

}  // namespace

ReturnLanding landOnReturns(const SweepReturns& sweep, const Eigen::Vector3d& q, double range_sigma_m,
                            double max_incidence_deg) {
  return land(sweep, q, range_sigma_m, std::tan(max_incidence_deg * M_PI / 180.0));
}

namespace {

using detail::FreeSpaceCounts;

FreeSpaceCounts freeSpaceCounts(const SweepReturns& from, const SweepReturns& to, const Isometry3& T_to_from,
                                double range_sigma_m, double max_incidence_deg) {
  const double max_tan = std::tan(max_incidence_deg * M_PI / 180.0);
  FreeSpaceCounts n;
  for (int r = 0; r < from.rows(); ++r)
    for (int c = 0; c < from.cols(); ++c) {
      const Eigen::Vector3d& p = from.point(r, c);
      if (!p.allFinite()) continue;
      const ReturnLanding l = land(to, T_to_from * p, range_sigma_m, max_tan);
      if (l.index < 0) continue;
      if (l.beyond_m < -l.gate_m) ++n.violations;
      else if (l.beyond_m > l.gate_m) ++n.occluded;
      else ++n.consistent;
    }
  return n;
}

}  // namespace

VisibilityCheck returnsFreeSpace(const SweepReturns& source, const SweepReturns& target, const Isometry3& T_target_source,
                                 const VisibilityCheckParams& params, double range_sigma_m, double max_incidence_deg) {
  VisibilityCheck check;
  if (!T_target_source.matrix().allFinite()) {
    check.reason = "free space on the returns: the pose is not finite";
    return check;
  }
  const FreeSpaceCounts ab = freeSpaceCounts(source, target, T_target_source, range_sigma_m, max_incidence_deg);
  const FreeSpaceCounts ba = freeSpaceCounts(target, source, T_target_source.inverse(), range_sigma_m, max_incidence_deg);
  detail::decideFreeSpace(ab, ba, params, {"free space on the returns", "returns", "sweep"}, check);
  return check;
}

}  // namespace gasp
