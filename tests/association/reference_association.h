#pragma once
// Test/benchmark helper: the first implementation of associateFeatureSets() (full OSA DP with
// FeatureMatch on doubles, KD-tree over plain normalised means, full B -> A pass for the mutual
// check), kept verbatim as the "before" of docs/association.md and as a reference. Not for
// production use.
#include <nanoflann.hpp>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <array>
#include <atomic>
#include <limits>
#include <vector>

#include "gasp/association/view_association.h"

namespace gasp::test::reference {

using Mean = std::array<double, 7>;

inline Mean normalisedMean(const std::vector<Feature>& q, const MatchParams& m) {
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

inline std::vector<PatchAssociation> bestPartners(const std::vector<std::vector<Feature>>& from,
                                                  const std::vector<std::vector<Feature>>& to,
                                                  const AssociationParams& p, std::size_t& comparisons_out) {
  MeanCloud cloud;
  std::vector<std::uint32_t> index_to;
  for (std::size_t j = 0; j < to.size(); ++j) {
    if (to[j].empty()) continue;
    cloud.points.push_back(normalisedMean(to[j], p.match));
    index_to.push_back(static_cast<std::uint32_t>(j));
  }
  MeanTree tree(7, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(10));
  tree.buildIndex();
  const std::size_t C = std::min<std::size_t>(static_cast<std::size_t>(p.candidates), cloud.points.size());
  std::vector<PatchAssociation> best(from.size());
  std::atomic<std::size_t> comparisons{0};
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
    for (std::size_t c = 0; c < found; ++c) {
      const int j = static_cast<int>(index_to[idx[c]]);
      const auto& q_to = to[static_cast<std::size_t>(j)];
      const double denom = static_cast<double>(from[i].size() + q_to.size());
      const double d = featureSetDistance(from[i], q_to, p.match, p.costs, std::min(p.lambda, best_hat) * denom, ws);
      if (d == kExceedsBound) continue;
      const double hat = d / denom;
      if (hat < best_hat || (hat == best_hat && j < best_j)) {
        best_hat = hat;
        best_j = j;
      }
    }
    comparisons += found;
    if (best_j >= 0 && best_hat <= p.lambda) best[i] = {static_cast<int>(i), best_j, best_hat};
  });
  comparisons_out += comparisons;
  return best;
}

/// The original associateFeatureSets() (associations only).
[[gnu::noinline]] inline std::vector<PatchAssociation> associate(const std::vector<std::vector<Feature>>& qa,
                                               const std::vector<std::vector<Feature>>& qb,
                                               const AssociationParams& p, std::size_t* comparisons = nullptr) {
  std::size_t n = 0;
  const auto a_to_b = bestPartners(qa, qb, p, n);
  std::vector<PatchAssociation> b_to_a;
  if (p.mutual_check) b_to_a = bestPartners(qb, qa, p, n);
  std::vector<PatchAssociation> out;
  for (const auto& s : a_to_b) {
    if (s.b < 0) continue;
    if (p.mutual_check && b_to_a[static_cast<std::size_t>(s.b)].b != s.a) continue;
    out.push_back(s);
  }
  if (comparisons) *comparisons = n;
  return out;
}

}  // namespace gasp::test::reference
