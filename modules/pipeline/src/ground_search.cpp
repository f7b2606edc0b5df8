#include "gasp/pipeline/ground_search.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "gasp/core/error.h"
#include "gasp/pipeline/returns_stage.h"

namespace gasp {
namespace {

constexpr double kDeg = M_PI / 180.0;

/// A sweep seen from its ground: the ground frame (origin under the sensor, z up the ground's
/// normal, x the sensor's x laid on the ground; sensor_from_ground maps it into the sensor's
/// frame) and the upright returns in it, one mean point per cell of `cell_m`.
struct GroundView {
  Isometry3 sensor_from_ground = Isometry3::Identity();
  std::vector<Eigen::Vector2d> fine;    ///< per fine cell
  std::vector<Eigen::Vector2d> coarse;  ///< per coarse cell
  std::string reason;                   ///< why there is no ground (a ground without upright cells leaves it empty)
};

/// A return on the ground's side of the sweep: its point, the normal of the cell it spans with the
/// next row's return and its row's neighbours, and that cell's area.
struct GroundCell {
  Eigen::Vector3d point, normal;
  double area_m2;
};

/// The nearest return in `row` within two columns of `col` on one side (a dual-return sweep leaves
/// every other column empty); null where there is none.
const Eigen::Vector3d* besideIn(const SweepReturns& s, int row, int col, int side) {
  for (int k = 1; k <= 2; ++k) {
    const int c = col + side * k;
    if (c < 0 || c >= s.cols()) return nullptr;
    if (const Eigen::Vector3d& q = s.point(row, c); q.allFinite()) return &q;
  }
  return nullptr;
}

/// The cells facing up within max_ground_tilt_deg of the sensor's axis. A cell is spanned by a
/// return, the return of the next row in its column and its row's neighbours: the rows of a
/// sweep lie far apart on the ground (a metre at 8 m for 2 deg), farther than a surface normal's
/// neighbourhood reaches, so the ground's cells are not taken from the returns' normals.
std::vector<GroundCell> upCells(const SweepReturns& s, double max_tilt_deg) {
  const double cos_tilt = std::cos(max_tilt_deg * kDeg);
  std::vector<GroundCell> cells;
  for (int r = 0; r + 1 < s.rows(); ++r)
    for (int c = 0; c < s.cols(); ++c) {
      const Eigen::Vector3d& p = s.point(r, c);
      const Eigen::Vector3d& q = s.point(r + 1, c);
      if (!p.allFinite() || !q.allFinite()) continue;
      const Eigen::Vector3d* left = besideIn(s, r, c, -1);
      const Eigen::Vector3d* right = besideIn(s, r, c, 1);
      if (!left || !right) continue;
      const Eigen::Vector3d along = *right - *left, across = q - p;
      if (along.norm() > 0.1 * p.norm()) continue;  // a depth edge in the row
      Eigen::Vector3d n = along.cross(across);
      const double area = 0.5 * n.norm();
      if (!(area > 0.0)) continue;
      n /= 2.0 * area;
      if (n.z() < 0.0) n = -n;
      if (n.z() >= cos_tilt && n.dot(p) < 0.0) cells.push_back({p, n, area});  // facing up, below the sensor
    }
  return cells;
}

/// The ground plane (unit normal facing up, offset: n.p = offset on it) of a sweep: the
/// area-weighted mode of the up-facing cells' heights along their mean normal, then two weighted
/// plane fits to the cells near it.
bool groundPlane(const SweepReturns& s, const GroundSearchParams& p, Eigen::Vector3d& n, double& offset) {
  const double cos_tilt = std::cos(p.max_ground_tilt_deg * kDeg);
  const std::vector<GroundCell> up = upCells(s, p.max_ground_tilt_deg);
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const GroundCell& g : up) mean += g.area_m2 * g.normal;
  if (up.size() < 10 || !(mean.norm() > 0.0)) return false;
  n = mean.normalized();
  // The most populated height bin along n.
  std::unordered_map<long, double> bins;
  for (const GroundCell& g : up) bins[std::lround(n.dot(g.point) / p.ground_bin_m)] += g.area_m2;
  const auto mode = std::max_element(bins.begin(), bins.end(), [](const auto& a, const auto& b) {
    return a.second < b.second || (a.second == b.second && a.first < b.first);
  });
  offset = static_cast<double>(mode->first) * p.ground_bin_m;
  for (int fit = 0; fit < 2; ++fit) {
    const double gate = fit == 0 ? 2.0 * p.ground_bin_m : p.ground_bin_m;
    double w_sum = 0.0;
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    Eigen::Matrix3d outer = Eigen::Matrix3d::Zero();
    for (const GroundCell& g : up) {
      if (std::abs(n.dot(g.point) - offset) > gate) continue;
      w_sum += g.area_m2, c += g.area_m2 * g.point, outer += g.area_m2 * g.point * g.point.transpose();
    }
    if (!(w_sum > 0.0)) return false;
    c /= w_sum;
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(outer / w_sum - c * c.transpose());
    Eigen::Vector3d fitted = eig.eigenvectors().col(0);
    if (fitted.dot(n) < 0.0) fitted = -fitted;
    if (fitted.z() < cos_tilt) return false;
    n = fitted;
    offset = n.dot(c);
  }
  return offset < 0.0;  // the sensor is above its ground
}

/// Mean point per grid cell of `cell_m`.
std::vector<Eigen::Vector2d> cellMeans(const std::vector<Eigen::Vector2d>& points, double cell_m) {
  std::unordered_map<std::uint64_t, std::pair<Eigen::Vector2d, int>> cells;
  for (const Eigen::Vector2d& q : points) {
    // Two 32-bit cell indices packed (unsigned: shifting a negative value is undefined).
    const auto ix = static_cast<std::uint32_t>(static_cast<std::int32_t>(std::floor(q.x() / cell_m)));
    const auto iy = static_cast<std::uint32_t>(static_cast<std::int32_t>(std::floor(q.y() / cell_m)));
    const std::uint64_t key = (static_cast<std::uint64_t>(ix) << 32) | iy;
    auto& [sum, count] = cells.try_emplace(key, Eigen::Vector2d::Zero(), 0).first->second;
    sum += q, ++count;
  }
  std::vector<Eigen::Vector2d> means;
  means.reserve(cells.size());
  for (const auto& [key, cell] : cells) means.push_back(cell.first / cell.second);
  // A fixed order, so the search does not depend on the hash map's.
  std::sort(means.begin(), means.end(), [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  return means;
}

GroundView groundView(const SweepReturns& s, const GroundSearchParams& p) {
  GroundView v;
  Eigen::Vector3d n;
  double offset = 0.0;
  if (!groundPlane(s, p, n, offset)) {
    v.reason = "no ground plane facing up within " + std::to_string(p.max_ground_tilt_deg) + " deg of the sensor's axis";
    return v;
  }
  Eigen::Vector3d x = Eigen::Vector3d::UnitX() - n.x() * n;
  if (x.norm() < 1e-6) x = Eigen::Vector3d::UnitY() - n.y() * n;
  x.normalize();
  Eigen::Matrix3d R;
  R << x, n.cross(x), n;
  v.sensor_from_ground.linear() = R;
  v.sensor_from_ground.translation() = offset * n;
  const Isometry3 ground_from_sensor = v.sensor_from_ground.inverse();
  const double max_normal_up = std::sin(p.max_upright_tilt_deg * kDeg);
  std::vector<Eigen::Vector2d> upright;
  for (int i = 0; i < s.rows() * s.cols(); ++i) {
    const Eigen::Vector3d& m = s.normal(i);
    if (m.isZero() || std::abs(m.dot(n)) > max_normal_up) continue;
    const Eigen::Vector3d g = ground_from_sensor * s.point(i);
    if (g.z() >= p.min_height_m && g.head<2>().norm() <= p.max_range_m) upright.push_back(g.head<2>());
  }
  v.fine = cellMeans(upright, p.fine_cell_m);
  v.coarse = cellMeans(upright, p.coarse_cell_m);
  return v;
}

/// The target's upright cells as a field on a grid of fine_cell_m: at each grid cell, a Gaussian
/// (sigma one cell, cut at two) of the distance from its centre to the nearest upright cell's
/// mean point, at least exp(-1/4) on a cell holding one. Empty points: zero everywhere.
class Field {
 public:
  Field(const std::vector<Eigen::Vector2d>& points, double cell_m) : cell_(cell_m) {
    if (points.empty()) return;
    Eigen::Vector2d lo = points.front(), hi = points.front();
    for (const auto& q : points) lo = lo.cwiseMin(q), hi = hi.cwiseMax(q);
    origin_ = lo - Eigen::Vector2d::Constant(3.0 * cell_);
    w_ = static_cast<int>(std::ceil((hi.x() - origin_.x()) / cell_)) + 4;
    h_ = static_cast<int>(std::ceil((hi.y() - origin_.y()) / cell_)) + 4;
    v_.assign(static_cast<std::size_t>(w_) * static_cast<std::size_t>(h_), 0.0f);
    for (const auto& q : points) {
      const double fx = (q.x() - origin_.x()) / cell_, fy = (q.y() - origin_.y()) / cell_;
      const int cx = static_cast<int>(fx), cy = static_cast<int>(fy);
      for (int dy = -2; dy <= 2; ++dy)
        for (int dx = -2; dx <= 2; ++dx) {
          const int x = cx + dx, y = cy + dy;
          if (x < 0 || y < 0 || x >= w_ || y >= h_) continue;
          const double ex = x + 0.5 - fx, ey = y + 0.5 - fy;
          float& cell = v_[static_cast<std::size_t>(y) * static_cast<std::size_t>(w_) + static_cast<std::size_t>(x)];
          cell = std::max(cell, static_cast<float>(std::exp(-0.5 * (ex * ex + ey * ey))));
        }
    }
  }
  double at(const Eigen::Vector2d& q) const {
    const int x = static_cast<int>(std::floor((q.x() - origin_.x()) / cell_));
    const int y = static_cast<int>(std::floor((q.y() - origin_.y()) / cell_));
    if (x < 0 || y < 0 || x >= w_ || y >= h_) return 0.0;
    return v_[static_cast<std::size_t>(y) * static_cast<std::size_t>(w_) + static_cast<std::size_t>(x)];
  }

 private:
  double cell_;
  Eigen::Vector2d origin_ = Eigen::Vector2d::Zero();
  int w_ = 0, h_ = 0;
  std::vector<float> v_;
};

struct Peak {
  double yaw = 0.0;  ///< [rad]
  Eigen::Vector2d t = Eigen::Vector2d::Zero();
  double score = 0.0;
};

bool distinct(const Peak& a, const Peak& b, const GroundSearchParams& p) {
  const double dyaw = std::abs(std::remainder(a.yaw - b.yaw, 2.0 * M_PI));
  return (a.t - b.t).norm() > p.distinct_m || dyaw > p.distinct_deg * kDeg;
}

double scoreAt(const Field& field, const std::vector<Eigen::Vector2d>& source, double yaw, const Eigen::Vector2d& t) {
  if (source.empty()) return 0.0;
  const Eigen::Rotation2Dd R(yaw);
  double sum = 0.0;
  for (const auto& q : source) sum += field.at(R * q + t);
  return sum / static_cast<double>(source.size());
}

/// The coarse vote: for every yaw, each source coarse cell votes once for every offset bin that
/// carries one of the target's coarse cells onto it; each yaw's best bins become candidates.
std::vector<Peak> coarsePeaks(const GroundView& s, const GroundView& t, const GroundSearchParams& p) {
  const double c = p.coarse_cell_m;
  const int M = static_cast<int>(std::ceil(p.max_offset_m / c));
  const int side = 2 * M + 1;
  std::vector<int> votes(static_cast<std::size_t>(side) * static_cast<std::size_t>(side));
  std::vector<int> stamp(votes.size());
  std::vector<Peak> candidates;
  const int yaws = std::max(1, static_cast<int>(std::lround(360.0 / p.coarse_yaw_deg)));
  int mark = 0;
  for (int k = 0; k < yaws; ++k) {
    const double yaw = 2.0 * M_PI * k / yaws;
    const Eigen::Rotation2Dd R(yaw);
    std::fill(votes.begin(), votes.end(), 0);
    for (const auto& q : s.coarse) {
      ++mark;
      const Eigen::Vector2d rq = R * q;
      for (const auto& u : t.coarse) {
        const int bx = static_cast<int>(std::lround((u.x() - rq.x()) / c)) + M;
        const int by = static_cast<int>(std::lround((u.y() - rq.y()) / c)) + M;
        if (bx < 0 || by < 0 || bx >= side || by >= side) continue;
        const std::size_t b = static_cast<std::size_t>(by) * static_cast<std::size_t>(side) + static_cast<std::size_t>(bx);
        if (stamp[b] != mark) stamp[b] = mark, ++votes[b];
      }
    }
    // This yaw's best bins (3 x 3 sums, local maxima), a few per yaw.
    std::vector<Peak> here;
    for (int by = 1; by + 1 < side; ++by)
      for (int bx = 1; bx + 1 < side; ++bx) {
        const int v = votes[static_cast<std::size_t>(by) * static_cast<std::size_t>(side) + static_cast<std::size_t>(bx)];
        if (v < 3) continue;
        int sum = 0;
        bool is_max = true;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const int w = votes[static_cast<std::size_t>(by + dy) * static_cast<std::size_t>(side) + static_cast<std::size_t>(bx + dx)];
            sum += w;
            if (w > v) is_max = false;
          }
        if (is_max) here.push_back({yaw, Eigen::Vector2d((bx - M) * c, (by - M) * c), static_cast<double>(sum)});
      }
    const std::size_t keep = std::min<std::size_t>(here.size(), 3);
    std::partial_sort(here.begin(), here.begin() + static_cast<long>(keep), here.end(),
                      [](const Peak& a, const Peak& b) { return a.score > b.score; });
    candidates.insert(candidates.end(), here.begin(), here.begin() + static_cast<long>(keep));
  }
  std::sort(candidates.begin(), candidates.end(), [](const Peak& a, const Peak& b) { return a.score > b.score; });
  // The best candidates, distinct from one another.
  std::vector<Peak> peaks;
  for (const Peak& q : candidates) {
    if (static_cast<int>(peaks.size()) >= p.peaks) break;
    if (std::all_of(peaks.begin(), peaks.end(), [&](const Peak& o) { return distinct(q, o, p); })) peaks.push_back(q);
  }
  return peaks;
}

/// A coarse peak refined on the field: yaw steps of half a degree over +-coarse_yaw_deg and offset
/// steps of one fine cell over +-coarse_cell_m, then a quarter of each around the best.
Peak refinePeak(const Peak& start, const Field& field, const std::vector<Eigen::Vector2d>& source,
                const GroundSearchParams& p) {
  Peak best = start;
  best.score = scoreAt(field, source, start.yaw, start.t);
  double yaw_step = 0.5 * kDeg, step = p.fine_cell_m;
  int yaw_n = static_cast<int>(std::ceil(p.coarse_yaw_deg * kDeg / yaw_step));
  int t_n = static_cast<int>(std::ceil(p.coarse_cell_m / step));
  for (int level = 0; level < 2; ++level) {
    const Peak centre = best;
    for (int a = -yaw_n; a <= yaw_n; ++a)
      for (int iy = -t_n; iy <= t_n; ++iy)
        for (int ix = -t_n; ix <= t_n; ++ix) {
          const double yaw = centre.yaw + a * yaw_step;
          const Eigen::Vector2d t = centre.t + step * Eigen::Vector2d(ix, iy);
          const double score = scoreAt(field, source, yaw, t);
          if (score > best.score) best = {yaw, t, score};
        }
    yaw_step *= 0.25, step *= 0.25;
    yaw_n = t_n = 4;
  }
  return best;
}

}  // namespace

void validate(const GroundSearchParams& p) {
  auto positive = [](double v, const char* name) {
    if (!(v > 0.0) || !std::isfinite(v)) throw Error(std::string("ground_search.") + name + " must be positive and finite");
  };
  auto angle = [](double v, const char* name) {
    if (!(v > 0.0 && v < 90.0)) throw Error(std::string("ground_search.") + name + " must be in (0, 90) deg");
  };
  angle(p.max_ground_tilt_deg, "max_ground_tilt_deg");
  angle(p.max_upright_tilt_deg, "max_upright_tilt_deg");
  if (!(p.ground_bin_m >= 0.01 && p.ground_bin_m <= 1.0)) throw Error("ground_search.ground_bin_m must be in [0.01, 1] m");
  if (!(p.min_height_m >= 0.0) || !std::isfinite(p.min_height_m)) throw Error("ground_search.min_height_m must be >= 0");
  positive(p.max_range_m, "max_range_m");
  positive(p.coarse_cell_m, "coarse_cell_m");
  positive(p.fine_cell_m, "fine_cell_m");
  // The bounds keep the grids and the vote to sizes a pair can afford.
  if (!(p.fine_cell_m <= p.coarse_cell_m && p.coarse_cell_m <= 20.0 * p.fine_cell_m))
    throw Error("ground_search.fine_cell_m must be at most coarse_cell_m and at least a 20th of it");
  if (!(p.max_range_m <= 2000.0 * p.fine_cell_m)) throw Error("ground_search.max_range_m must be at most 2000 fine cells");
  if (!(p.coarse_yaw_deg >= 0.1 && p.coarse_yaw_deg <= 30.0)) throw Error("ground_search.coarse_yaw_deg must be in [0.1, 30]");
  positive(p.max_offset_m, "max_offset_m");
  // Two sensors that see common structure within max_range_m each are at most twice it apart.
  if (!(p.max_offset_m <= 2.0 * p.max_range_m)) throw Error("ground_search.max_offset_m must be at most twice max_range_m");
  if (p.max_offset_m / p.coarse_cell_m > 500.0)
    throw Error("ground_search.max_offset_m must be at most 500 coarse cells (coarse_cell_m)");
  if (p.peaks < 1) throw Error("ground_search.peaks must be >= 1");
  positive(p.distinct_m, "distinct_m");
  if (!(p.distinct_deg > 0.0 && p.distinct_deg < 180.0)) throw Error("ground_search.distinct_deg must be in (0, 180)");
  if (p.min_cells < 3) throw Error("ground_search.min_cells must be >= 3");
  if (!(p.min_score > 0.0 && p.min_score <= 1.0)) throw Error("ground_search.min_score must be in (0, 1]");
}

GroundSearchResult groundSearch(const SweepReturns& source, const SweepReturns& target, const GroundSearchParams& p) {
  const auto t0 = std::chrono::steady_clock::now();
  GroundSearchResult r;
  const auto done = [&]() -> GroundSearchResult& {
    r.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    return r;
  };
  const GroundView s = groundView(source, p), t = groundView(target, p);
  r.source_cells = static_cast<int>(s.fine.size());
  r.target_cells = static_cast<int>(t.fine.size());
  if (!s.reason.empty() || !t.reason.empty()) {
    r.reason = "ground search: " + (s.reason.empty() ? "target: " + t.reason : "source: " + s.reason);
    return done();
  }
  if (r.source_cells < p.min_cells || r.target_cells < p.min_cells) {
    r.reason = "ground search: " + std::to_string(r.source_cells) + " and " + std::to_string(r.target_cells) +
               " upright cells, fewer than min_cells " + std::to_string(p.min_cells);
    return done();
  }
  const Field field(t.fine, p.fine_cell_m);
  std::vector<Peak> refined;
  for (const Peak& q : coarsePeaks(s, t, p)) refined.push_back(refinePeak(q, field, s.fine, p));
  std::sort(refined.begin(), refined.end(), [](const Peak& a, const Peak& b) { return a.score > b.score; });
  if (refined.empty() || refined.front().score < p.min_score) {
    r.reason = "ground search: the best pose lands " + std::to_string(refined.empty() ? 0.0 : refined.front().score) +
               " of the source's upright cells, less than min_score " + std::to_string(p.min_score);
    return done();
  }
  const auto pose = [&](const Peak& q) {
    Isometry3 G = Isometry3::Identity();  // target ground <- source ground
    G.linear() = Eigen::AngleAxisd(q.yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    G.translation() << q.t, 0.0;
    return Isometry3(t.sensor_from_ground * G * s.sensor_from_ground.inverse());
  };
  r.found = true;
  r.score = refined.front().score;
  r.T_target_source = pose(refined.front());
  for (std::size_t k = 1; k < refined.size(); ++k)
    if (distinct(refined[k], refined.front(), p) && refined[k].score >= p.min_score) {
      r.runner_up = pose(refined[k]);
      r.runner_up_score = refined[k].score;
      break;
    }
  return done();
}

double groundSearchScore(const SweepReturns& source, const SweepReturns& target, const Isometry3& T_target_source,
                         const GroundSearchParams& p) {
  const GroundView s = groundView(source, p), t = groundView(target, p);
  if (s.fine.empty() || t.fine.empty()) return 0.0;
  const Field field(t.fine, p.fine_cell_m);
  const Isometry3 G = t.sensor_from_ground.inverse() * T_target_source * s.sensor_from_ground;
  double sum = 0.0;
  for (const auto& q : s.fine) sum += field.at((G * Eigen::Vector3d(q.x(), q.y(), 0.0)).head<2>());
  return sum / static_cast<double>(s.fine.size());
}

}  // namespace gasp
