#include "gasp/association/view_association.h"

#include <nanoflann.hpp>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <array>
#include <atomic>
#include <chrono>
#include <cmath>

#include "gasp/core/error.h"

namespace gasp {

namespace {

using Mean = std::array<double, 7>;

/// Q_bar: mean of a feature set with distances divided by r_dev and angles by theta_dev, so one
/// unit is one match tolerance in every component.
Mean normalisedMean(const std::vector<Feature>& q, const MatchParams& m) {
  Mean mean{};
  for (const auto& f : q)
    for (std::size_t c = 0; c < 7; ++c) mean[c] += f[c];
  for (std::size_t c = 0; c < 7; ++c)
    mean[c] /= static_cast<double>(q.size()) * (c < kFeatureDistanceComponents ? m.r_dev_m : m.theta_dev_rad);
  return mean;
}

struct MeanCloud {
  std::vector<Mean> points;
  std::size_t kdtree_get_point_count() const { return points.size(); }
  double kdtree_get_pt(std::size_t i, std::size_t dim) const { return points[i][dim]; }
  template <class BBox>
  bool kdtree_get_bbox(BBox&) const { return false; }
};

using MeanTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, MeanCloud>,
                                                     MeanCloud, 7, std::uint32_t>;

double msSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

void validate(const AssociationParams& p) {
  validate(p.feature_sets);
  validate(p.match);
  validate(p.costs);
  if (p.candidates < 1) throw Error("association: candidates (C) must be >= 1");
  if (!(p.lambda >= 0.0 && p.lambda <= 1.0)) throw Error("association: lambda must be in [0, 1]");
}

namespace {

/// For every patch of `from`, its best partner in `to` (b = -1 where none), D_hat-gated; adds to
/// the statistics.
std::vector<PatchAssociation> bestPartners(const std::vector<std::vector<Feature>>& from,
                                           const std::vector<std::vector<Feature>>& to,
                                           const AssociationParams& p, AssociationStats& stats) {
  const auto t_tree = std::chrono::steady_clock::now();
  MeanCloud cloud;
  std::vector<std::uint32_t> index_to;  // tree point -> patch of `to`
  for (std::size_t j = 0; j < to.size(); ++j) {
    if (to[j].empty()) continue;
    cloud.points.push_back(normalisedMean(to[j], p.match));
    index_to.push_back(static_cast<std::uint32_t>(j));
  }
  MeanTree tree(7, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(10));
  tree.buildIndex();
  stats.tree_ms += msSince(t_tree);

  const auto t_match = std::chrono::steady_clock::now();
  const std::size_t C = std::min<std::size_t>(static_cast<std::size_t>(p.candidates), cloud.points.size());
  std::vector<PatchAssociation> best(from.size());
  std::vector<unsigned char> gated(from.size(), 0);
  std::atomic<std::size_t> comparisons{0}, cut{0};
  tbb::enumerable_thread_specific<EditDistanceWorkspace> workspaces;
  tbb::parallel_for(std::size_t{0}, from.size(), [&](std::size_t i) {
    if (from[i].empty()) return;
    auto& ws = workspaces.local();
    const Mean query = normalisedMean(from[i], p.match);
    std::vector<std::uint32_t> idx(C);
    std::vector<double> dist(C);
    const std::size_t found = tree.knnSearch(query.data(), C, idx.data(), dist.data());
    double best_hat = std::numeric_limits<double>::infinity();
    int best_j = -1;
    std::size_t local_cut = 0;
    for (std::size_t c = 0; c < found; ++c) {
      const int j = static_cast<int>(index_to[idx[c]]);
      const auto& q_to = to[static_cast<std::size_t>(j)];
      const double denom = static_cast<double>(from[i].size() + q_to.size());
      // Bound lambda (k_S + k_S'), tightened to the best found so far.
      const double d = featureSetDistance(from[i], q_to, p.match, p.costs, std::min(p.lambda, best_hat) * denom, ws);
      if (d == kExceedsBound) {
        ++local_cut;
        continue;
      }
      const double hat = d / denom;
      if (hat < best_hat || (hat == best_hat && j < best_j)) {
        best_hat = hat;
        best_j = j;
      }
    }
    comparisons += found;
    cut += local_cut;
    if (best_j >= 0 && best_hat <= p.lambda) best[i] = {static_cast<int>(i), best_j, best_hat};
    else if (found > 0) gated[i] = 1;
  });
  stats.comparisons += comparisons;
  stats.cut_early += cut;
  for (unsigned char g : gated) stats.gated_out += g;
  stats.matching_ms += msSince(t_match);
  return best;
}

}  // namespace

AssociationResult associateFeatureSets(const std::vector<std::vector<Feature>>& qa,
                                       const std::vector<std::vector<Feature>>& qb,
                                       const AssociationParams& p) {
  validate(p);
  AssociationResult r;
  r.stats.patches_a = qa.size();
  r.stats.patches_b = qb.size();
  for (const auto& q : qa) r.stats.with_features_a += !q.empty();
  for (const auto& q : qb) r.stats.with_features_b += !q.empty();
  if (r.stats.with_features_a == 0 || r.stats.with_features_b == 0) {
    r.reason = "a view has no patch with a feature set (needs at least two usable patches)";
    return r;
  }
  r.stats.comparisons_full = r.stats.with_features_a * r.stats.with_features_b * (p.mutual_check ? 2 : 1);
  const auto a_to_b = bestPartners(qa, qb, p, r.stats);
  std::vector<PatchAssociation> b_to_a;
  if (p.mutual_check) b_to_a = bestPartners(qb, qa, p, r.stats);
  for (const auto& s : a_to_b) {
    if (s.b < 0) continue;
    if (p.mutual_check && b_to_a[static_cast<std::size_t>(s.b)].b != s.a) {
      ++r.stats.not_mutual;
      continue;
    }
    r.associations.push_back(s);
  }
  if (r.associations.empty()) r.reason = "no candidate within the gating distance lambda";
  return r;
}

AssociationResult associateViews(const std::vector<PatchGeometry>& a, const std::vector<PatchGeometry>& b,
                                 const AssociationParams& p) {
  validate(p);
  const auto t0 = std::chrono::steady_clock::now();
  const auto qa = computeFeatureSets(a, p.feature_sets);
  const auto qb = computeFeatureSets(b, p.feature_sets);
  const double features_ms = msSince(t0);
  AssociationResult r = associateFeatureSets(qa, qb, p);
  r.stats.features_ms = features_ms;
  return r;
}

}  // namespace gasp
