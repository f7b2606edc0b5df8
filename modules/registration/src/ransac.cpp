#include "gasp/registration/ransac.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <random>

#include "gasp/core/error.h"
#include "compatibility_graph.h"
#include "rigid_fit.h"

namespace gasp {
namespace {

using Sample = std::array<int, 3>;

enum class SampleCheck { kOk, kThin, kInconsistent };

double angleBetween(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::acos(std::clamp(a.dot(b), -1.0, 1.0));
}

/// Rigid motions preserve distances and angles; a thin triangle leaves rotation ill-determined.
SampleCheck checkSample(const std::vector<PatchCorrespondence>& c, const Sample& s, const RansacParams& params) {
  const auto& a = c[s[0]].p_source;
  const auto& b = c[s[1]].p_source;
  const auto& d = c[s[2]].p_source;
  const double longest = std::max({(b - a).norm(), (d - a).norm(), (d - b).norm()});
  const double height = (b - a).cross(d - a).norm() / std::max(longest, 1e-300);  // 2 area / base
  if (height < params.min_triangle_height_m) return SampleCheck::kThin;
  const double max_angle = params.normal_pair_tolerance_deg * M_PI / 180.0;
  for (int u = 0; u < 3; ++u) {
    const auto& ci = c[s[u]];
    const auto& cj = c[s[(u + 1) % 3]];
    const double ds = (ci.p_source - cj.p_source).norm(), dt = (ci.p_target - cj.p_target).norm();
    if (std::abs(ds - dt) > params.edge_tolerance_m) return SampleCheck::kInconsistent;
    const double as = angleBetween(ci.n_source, cj.n_source), at = angleBetween(ci.n_target, cj.n_target);
    if (std::abs(as - at) > max_angle) return SampleCheck::kInconsistent;
  }
  return SampleCheck::kOk;
}

Isometry3 fitSample(const std::vector<PatchCorrespondence>& c, const Sample& s) {
  Eigen::Matrix3d src, dst;
  for (int k = 0; k < 3; ++k) {
    src.col(k) = c[s[k]].p_source;
    dst.col(k) = c[s[k]].p_target;
  }
  Isometry3 T;
  T.matrix() = Eigen::umeyama(src, dst, false);
  return T;
}

struct Score {
  int inliers = 0;
  double cost = std::numeric_limits<double>::infinity();  // MSAC: sum min(d^2 / d_max^2, 1)
  bool betterThan(const Score& o) const { return inliers > o.inliers || (inliers == o.inliers && cost < o.cost); }
};

Score score(const std::vector<PatchCorrespondence>& c, const Isometry3& T, const InlierCriterion& criterion) {
  Score sc;
  sc.cost = 0.0;
  const double max_sq = criterion.distance_m * criterion.distance_m;
  for (const auto& ci : c) {
    const double sq = (T * ci.p_source - ci.p_target).squaredNorm();
    if (isInlier(ci, T, criterion)) {
      ++sc.inliers;
      sc.cost += sq / max_sq;
    } else {
      sc.cost += 1.0;
    }
  }
  return sc;
}

/// Samples needed for `confidence` of one all-inlier sample when one sample is all-inlier with
/// probability all_inlier: log(1 - confidence) / log(1 - all_inlier).
int adaptiveIterations(double all_inlier, const RansacParams& params) {
  if (all_inlier >= 1.0) return 1;
  if (!(all_inlier > 0.0)) return params.max_iterations;
  const double n = std::ceil(std::log1p(-params.confidence) / std::log1p(-all_inlier));
  if (!std::isfinite(n) || n >= params.max_iterations) return params.max_iterations;  // P below ~1e-16
  return std::max(1, static_cast<int>(n));
}

/// The best models sampled, one per distinct placement of the source centroids (at most kMaxModes,
/// the worst dropped): where the best distinct alternative comes from.
class Modes {
 public:
  static constexpr std::size_t kMaxModes = 16;
  Modes(const std::vector<PatchCorrespondence>& c, double distinct_m) : distinct_m_(distinct_m) {
    std::vector<Eigen::Vector3d> points;
    points.reserve(c.size());
    for (const auto& ci : c) points.push_back(ci.p_source);
    spread_ = pointSpread(points);
  }
  bool distinct(const Isometry3& a, const Isometry3& b, double apart_m) const {
    return rmsDisplacement(a, b, spread_) > apart_m;
  }
  void add(const Isometry3& T, const Score& sc) {
    for (auto& m : modes_)
      if (!distinct(m.T, T, distinct_m_)) {
        if (sc.betterThan(m.sc)) m = {T, sc};
        return;
      }
    modes_.push_back({T, sc});
    if (modes_.size() <= kMaxModes) return;
    const auto worst = std::min_element(modes_.begin(), modes_.end(),
                                        [](const Mode& x, const Mode& y) { return y.sc.betterThan(x.sc); });
    modes_.erase(worst);
  }
  /// The modes more than apart_m from T, best first.
  std::vector<Isometry3> distinctFrom(const Isometry3& T, double apart_m) const {
    std::vector<Mode> d;
    for (const auto& m : modes_)
      if (distinct(m.T, T, apart_m)) d.push_back(m);
    std::sort(d.begin(), d.end(), [](const Mode& x, const Mode& y) { return x.sc.betterThan(y.sc); });
    std::vector<Isometry3> out;
    for (const auto& m : d) out.push_back(m.T);
    return out;
  }

 private:
  struct Mode {
    Isometry3 T;
    Score sc;
  };
  double distinct_m_;
  PointSpread spread_;
  std::vector<Mode> modes_;
};

/// Re-fits T on its inliers (weighted least squares) and recounts them, twice.
std::vector<int> refit(const std::vector<PatchCorrespondence>& c, const RansacParams& params, Isometry3& T) {
  std::vector<int> inliers = selectInliers(c, T, params.inlier);
  for (int round = 0; round < 2 && static_cast<int>(inliers.size()) >= params.min_inliers; ++round) {
    T = detail::fitRigid(c, inliers);
    std::vector<int> recount = selectInliers(c, T, params.inlier);
    const bool same = recount == inliers;
    inliers = std::move(recount);
    if (same) break;
  }
  return inliers;
}

Sample drawSample(std::mt19937& rng, int n) {
  std::uniform_int_distribution<int> pick(0, n - 1);
  Sample s{pick(rng), 0, 0};
  do s[1] = pick(rng); while (s[1] == s[0]);
  do s[2] = pick(rng); while (s[2] == s[0] || s[2] == s[1]);
  return s;
}

}  // namespace

void validate(const RansacParams& params) {
  validate(params.inlier);
  if (!(params.edge_tolerance_m > 0.0)) throw Error("RansacParams.edge_tolerance_m must be positive");
  if (!(params.normal_pair_tolerance_deg > 0.0 && params.normal_pair_tolerance_deg <= 180.0))
    throw Error("RansacParams.normal_pair_tolerance_deg must be in (0, 180]");
  if (!(params.min_triangle_height_m >= 0.0)) throw Error("RansacParams.min_triangle_height_m must be >= 0");
  if (params.min_inliers < 3) throw Error("RansacParams.min_inliers must be >= 3");
  if (params.max_iterations < 1) throw Error("RansacParams.max_iterations must be >= 1");
  if (params.min_iterations < 0) throw Error("RansacParams.min_iterations must be >= 0");
  if (params.max_guided_correspondences < 3) throw Error("RansacParams.max_guided_correspondences must be >= 3");
  if (!(params.confidence > 0.0 && params.confidence < 1.0)) throw Error("RansacParams.confidence must be in (0, 1)");
}

RansacResult ransacPose(const std::vector<PatchCorrespondence>& c, const RansacParams& params) {
  validate(params);
  RansacResult result;
  const int n = static_cast<int>(c.size());
  if (n < 3 || n < params.min_inliers) {
    result.reason = "too few correspondences: " + std::to_string(n) + " (need 3 and min_inliers " +
                    std::to_string(params.min_inliers) + ")";
    return result;
  }
  if (std::string why = invalidInput(c); !why.empty()) {
    result.reason = "invalid input: " + why;
    return result;
  }

  std::mt19937 rng(params.seed);
  Score best;
  Isometry3 best_T = Isometry3::Identity();
  Modes modes(c, params.inlier.distance_m);
  int thin = 0, misses = 0, needed = params.max_iterations;
  std::unique_ptr<detail::CompatibilityGraph> graph;
  if (params.guided_sampling && n <= params.max_guided_correspondences) {
    graph = std::make_unique<detail::CompatibilityGraph>(c, params.edge_tolerance_m,
                                                         params.normal_pair_tolerance_deg * M_PI / 180.0);
    if (graph->seeds().empty()) {
      result.reason = "no sample of 3 passed the checks (no correspondence agrees in distances and normal angles "
                      "with two others)";
      return result;
    }
  }
  for (result.iterations = 0; result.iterations < needed; ++result.iterations) {
    Sample s;
    if (graph && !graph->drawTriangle(rng, s[0], s[1], s[2])) {
      ++result.rejected_samples;
      ++misses;
      continue;
    }
    if (!graph) s = drawSample(rng, n);
    const SampleCheck check = checkSample(c, s, params);
    if (check != SampleCheck::kOk) {
      ++result.rejected_samples;
      thin += check == SampleCheck::kThin;
      continue;
    }
    const Isometry3 T = fitSample(c, s);
    const Score sc = score(c, T, params.inlier);
    if (sc.inliers >= params.min_inliers) modes.add(T, sc);
    if (sc.betterThan(best)) {
      best = sc;
      best_T = T;
      const double p_all_in = graph ? graph->probabilityAllIn(selectInliers(c, T, params.inlier))
                                    : std::pow(static_cast<double>(best.inliers) / n, 3);
      const int floor = graph ? std::min(params.min_iterations, params.max_iterations) : 0;
      needed = std::max({result.iterations + 1, floor, adaptiveIterations(p_all_in, params)});
    }
  }
  if (result.rejected_samples == result.iterations) {
    result.reason = thin > 0 && thin + misses == result.iterations
                        ? "centroids (nearly) collinear: no sample triangle has a height of min_triangle_height_m"
                        : "no sample of 3 passed the checks (distances or normal angles disagree between the views)";
    return result;
  }

  std::vector<int> inliers = refit(c, params, best_T);
  result.T_target_source = best_T;
  if (static_cast<int>(inliers.size()) < params.min_inliers) {
    result.reason = "no consensus: the best model has " + std::to_string(inliers.size()) +
                    " inliers, fewer than min_inliers " + std::to_string(params.min_inliers);
    return result;
  }
  result.inliers = std::move(inliers);
  result.success = true;
  for (Isometry3 T : modes.distinctFrom(best_T, 2.0 * params.inlier.distance_m)) {
    std::vector<int> alternative = refit(c, params, T);  // re-fitting may bring a mode near the best model
    if (static_cast<int>(alternative.size()) < params.min_inliers ||
        !modes.distinct(T, best_T, 2.0 * params.inlier.distance_m))
      continue;
    result.alternative_T_target_source = T;
    result.alternative_inliers = std::move(alternative);
    break;
  }
  return result;
}

}  // namespace gasp
