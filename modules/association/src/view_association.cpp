#include "gasp/association/view_association.h"

#include <nanoflann.hpp>
#if defined(__SSE2__) || defined(_M_X64)
#include <emmintrin.h>
#endif
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>

#include "gasp/association/banded_distance.h"
#include "gasp/core/error.h"
#include "gasp/core/stopwatch.h"

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

/// Quantile signature: for each component, its values at kSignatureQuantiles evenly spaced ranks
/// (linear interpolation between order statistics), in units of half the match tolerance, stored
/// as bytes (128 + round(2 value / tolerance), saturated at +-64 tolerances: +-2.56 m with the
/// defaults; angles never saturate), padded with 128 to 64 bytes. Compared with the L1 distance of the bytes
/// (exact integer sums, four SSE2 sum-of-absolute-differences instructions per pair).
constexpr std::size_t kSignatureQuantiles = 9;
constexpr std::size_t kSignatureStride = 64;
static_assert(7 * kSignatureQuantiles <= kSignatureStride, "signature does not fit");

void quantileSignature(const PreparedFeatureSet& set, const MatchParams& m, std::uint8_t* out) {
  std::fill(out, out + kSignatureStride, std::uint8_t{128});
  const std::size_t n = set.size();
  std::vector<double> v;
  for (std::size_t c = 0; c < 7; ++c) {
    if (!set.sorted_values.empty()) {
      v.assign(set.sorted_values.begin() + static_cast<std::ptrdiff_t>(c * n),
               set.sorted_values.begin() + static_cast<std::ptrdiff_t>((c + 1) * n));
    } else {  // non-finite values: the finite ones
      v.clear();
      for (const auto& f : set.features)
        if (std::isfinite(f[c])) v.push_back(f[c]);
      std::sort(v.begin(), v.end());
    }
    if (v.empty()) continue;
    const double tol = c < kFeatureDistanceComponents ? m.r_dev_m : m.theta_dev_rad;
    const double scale = tol > 0.0 ? 2.0 / tol : 2.0;
    for (std::size_t k = 0; k < kSignatureQuantiles; ++k) {
      const double pos = (static_cast<double>(k) + 0.5) / kSignatureQuantiles * static_cast<double>(v.size() - 1);
      const auto k0 = static_cast<std::size_t>(pos);
      const std::size_t k1 = std::min(k0 + 1, v.size() - 1);
      const double t = pos - static_cast<double>(k0);
      const double x = std::round((v[k0] * (1.0 - t) + v[k1] * t) * scale) + 128.0;
      out[c * kSignatureQuantiles + k] = static_cast<std::uint8_t>(std::isnan(x) ? 128.0 : std::clamp(x, 0.0, 255.0));
    }
  }
}

/// L1 distance of two byte signatures.
inline std::uint32_t signatureDistance(const std::uint8_t* x, const std::uint8_t* y) {
#if defined(__SSE2__) || defined(_M_X64)
  __m128i acc = _mm_setzero_si128();
  for (std::size_t d = 0; d < kSignatureStride; d += 16) {
    const __m128i a = _mm_loadu_si128(reinterpret_cast<const __m128i*>(x + d));
    const __m128i b = _mm_loadu_si128(reinterpret_cast<const __m128i*>(y + d));
    acc = _mm_add_epi64(acc, _mm_sad_epu8(a, b));
  }
  return static_cast<std::uint32_t>(_mm_cvtsi128_si32(acc) + _mm_cvtsi128_si32(_mm_srli_si128(acc, 8)));
#else
  std::uint32_t d = 0;
  for (std::size_t k = 0; k < kSignatureStride; ++k) d += static_cast<std::uint32_t>(std::abs(int{x[k]} - int{y[k]}));
  return d;
#endif
}

}  // namespace

void validate(const AssociationParams& p) {
  validate(p.feature_sets);
  validate(p.match);
  validate(p.costs);
  if (p.candidates < 1) throw Error("association: candidates (C) must be >= 1");
  if (!(p.lambda >= 0.0 && p.lambda <= 1.0)) throw Error("association: lambda must be in [0, 1]");
  if (!(p.distinctiveness_ratio > 0.0 && p.distinctiveness_ratio <= 1.0))
    throw Error("association: distinctiveness_ratio must be in (0, 1]");
}

namespace {

/// One view, ready for searching: prepared feature sets and the candidate index (a KD-tree over
/// the means, or the quantile signatures searched exhaustively).
struct SearchIndex {
  std::vector<PreparedFeatureSet> sets;  ///< per patch
  std::vector<std::uint32_t> point_to_patch;  ///< index point -> patch (patches with features)
  std::vector<std::uint32_t> patch_to_point;  ///< inverse (patches without features: unused)
  MeanCloud cloud;                         ///< CandidateKey::kMean
  std::unique_ptr<MeanTree> tree;
  std::vector<std::uint8_t> signatures;    ///< CandidateKey::kQuantiles, kSignatureStride per point
  std::size_t points() const { return point_to_patch.size(); }
};

void buildIndex(const std::vector<std::vector<Feature>>& q, const AssociationParams& p, bool searchable,
                SearchIndex& index) {
  index.sets.resize(q.size());
  index.patch_to_point.assign(q.size(), 0);
  for (std::size_t j = 0; j < q.size(); ++j) {
    if (q[j].empty()) continue;
    index.patch_to_point[j] = static_cast<std::uint32_t>(index.point_to_patch.size());
    index.point_to_patch.push_back(static_cast<std::uint32_t>(j));
  }
  // Signatures of every set (they are the queries too); the tree only where it is searched.
  const bool quantiles = p.candidate_key == CandidateKey::kQuantiles;
  if (quantiles) index.signatures.assign(index.points() * kSignatureStride, std::uint8_t{128});
  tbb::parallel_for(std::size_t{0}, q.size(), [&](std::size_t i) {
    index.sets[i] = prepareFeatureSet(q[i], p.match, p.feature_sets.ordering);
    if (quantiles && !q[i].empty())
      quantileSignature(index.sets[i], p.match, index.signatures.data() + index.patch_to_point[i] * kSignatureStride);
  });
  if (!searchable || quantiles) return;
  {
    for (const std::uint32_t j : index.point_to_patch) index.cloud.points.push_back(normalisedMean(q[j], p.match));
    index.tree = std::make_unique<MeanTree>(7, index.cloud, nanoflann::KDTreeSingleIndexAdaptorParams(10));
    index.tree->buildIndex();
  }
}

/// Per-thread scratch memory of the search.
struct SearchScratch {
  BandedWorkspace distance;
  std::vector<std::uint32_t> idx;
  std::vector<double> dist;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> ranked;  ///< (signature distance, point) heap
};

/// The C index points of `to` nearest to patch i of `from` under the candidate key, nearest first
/// (ties: lower index first), into scratch.idx; returns how many.
std::size_t findCandidates(const SearchIndex& from, std::size_t i, const SearchIndex& to, const AssociationParams& p,
                           std::size_t C, SearchScratch& scratch) {
  scratch.idx.resize(C);
  if (p.candidate_key == CandidateKey::kMean) {
    scratch.dist.resize(C);
    const Mean query = normalisedMean(from.sets[i].features, p.match);
    return to.tree->knnSearch(query.data(), C, scratch.idx.data(), scratch.dist.data());
  }
  // Exhaustive, keeping the best C in a max-heap on (distance, point).
  const std::uint8_t* query = from.signatures.data() + from.patch_to_point[i] * kSignatureStride;
  auto& heap = scratch.ranked;
  heap.clear();
  for (std::size_t k = 0; k < to.points(); ++k) {
    const std::pair<std::uint32_t, std::uint32_t> item{
        signatureDistance(query, to.signatures.data() + k * kSignatureStride), static_cast<std::uint32_t>(k)};
    if (heap.size() < C) {
      heap.push_back(item);
      std::push_heap(heap.begin(), heap.end());
    } else if (item < heap.front()) {
      std::pop_heap(heap.begin(), heap.end());
      heap.back() = item;
      std::push_heap(heap.begin(), heap.end());
    }
  }
  std::sort_heap(heap.begin(), heap.end());
  for (std::size_t c = 0; c < C; ++c) scratch.idx[c] = heap[c].second;
  return C;
}

/// Outcome of one search: the best partner (-1: none within lambda), comparisons made and cut.
struct SearchOutcome {
  int best = -1;
  double best_hat = std::numeric_limits<double>::infinity();
  double second_hat = std::numeric_limits<double>::infinity();  ///< with the ratio test only
  bool ambiguous = false;  ///< the best failed the distinctiveness ratio (best is then -1)
  std::size_t found = 0, cut = 0;
};

/// Bound on D for a candidate with denominator `denom` to be compared with `hat_limit`: loosened by
/// a relative 1e-9 so that rounding never cuts a candidate whose D_hat equals hat_limit (ties are
/// then decided by the patch index, whatever the evaluation order).
inline double tieSafeBound(double hat_limit, double denom) { return hat_limit * denom * (1.0 + 1e-9); }

/// (hat, index) lexicographic: x before y.
inline bool better(double hat_x, int x, double hat_y, int y) { return hat_x < hat_y || (hat_x == hat_y && x < y); }

/// The best partner in `to` of patch i of `from`: the least (D_hat, patch index) over the C
/// candidates, gated at lambda. The bound of each comparison is lambda (k_S + k_S') tightened to
/// the best so far, so early termination prunes candidates that cannot win.
SearchOutcome searchBest(const SearchIndex& from, std::size_t i, const SearchIndex& to, const AssociationParams& p,
                         SearchScratch& scratch) {
  SearchOutcome out;
  const PreparedFeatureSet& qi = from.sets[i];
  if (qi.empty() || to.points() == 0) return out;
  const std::size_t C = std::min<std::size_t>(static_cast<std::size_t>(p.candidates), to.points());
  out.found = findCandidates(from, i, to, p, C, scratch);
  const bool ratio_test = p.distinctiveness_ratio < 1.0;
  for (std::size_t c = 0; c < out.found; ++c) {
    const int j = static_cast<int>(to.point_to_patch[scratch.idx[c]]);
    const PreparedFeatureSet& qj = to.sets[static_cast<std::size_t>(j)];
    const double denom = static_cast<double>(qi.size() + qj.size());
    // With the ratio test the second best must be known too: bound by it instead of the best.
    const double limit = std::min(p.lambda, ratio_test ? out.second_hat : out.best_hat);
    const double d = featureSetDistance(qi, qj, p.match, p.costs, tieSafeBound(limit, denom), scratch.distance);
    if (d == kExceedsBound) {
      ++out.cut;
      continue;
    }
    const double hat = d / denom;
    if (hat > p.lambda) continue;
    if (better(hat, j, out.best_hat, out.best)) {
      out.second_hat = out.best_hat;
      out.best_hat = hat;
      out.best = j;
    } else if (hat < out.second_hat) {
      out.second_hat = hat;
    }
  }
  if (ratio_test && out.best >= 0 && !(out.best_hat < p.distinctiveness_ratio * out.second_hat)) {
    out.best = -1;
    out.ambiguous = true;
  }
  return out;
}

/// Mutual check of patch b of `to` (view B) chosen by the patches `chosen_by` of `from` (view A,
/// ascending): which of them, if any, is b's own best partner in A, exactly as searchBest(b)
/// would find it, without searching all of b's candidates in full: the choosers among b's
/// candidates are compared first, then every other candidate only needs to be checked against
/// the best of them (a tight bound: most are rejected by the matching bounds), and the check
/// stops at the first that beats it. Returns the confirmed patch of A or -1.
int mutualPartner(const SearchIndex& from, const SearchIndex& to, std::size_t b, const std::uint32_t* chosen_by,
                  std::size_t n_chosen, const AssociationParams& p, SearchScratch& scratch, SearchOutcome& stats) {
  const PreparedFeatureSet& qb = to.sets[b];
  const std::size_t C = std::min<std::size_t>(static_cast<std::size_t>(p.candidates), from.points());
  stats.found = findCandidates(to, b, from, p, C, scratch);
  double best_hat = std::numeric_limits<double>::infinity();
  int best = -1;
  const auto inChosen = [&](int a) { return std::binary_search(chosen_by, chosen_by + n_chosen, static_cast<std::uint32_t>(a)); };
  std::size_t compared = 0;
  for (std::size_t c = 0; c < stats.found; ++c) {
    const int a = static_cast<int>(from.point_to_patch[scratch.idx[c]]);
    if (!inChosen(a)) continue;
    const PreparedFeatureSet& qa = from.sets[static_cast<std::size_t>(a)];
    const double denom = static_cast<double>(qb.size() + qa.size());
    const double d = featureSetDistance(qb, qa, p.match, p.costs, tieSafeBound(std::min(p.lambda, best_hat), denom),
                                        scratch.distance);
    ++compared;
    if (d == kExceedsBound) {
      ++stats.cut;
      continue;
    }
    const double hat = d / denom;
    if (hat <= p.lambda && better(hat, a, best_hat, best)) {
      best_hat = hat;
      best = a;
    }
  }
  if (best < 0) {
    stats.found = compared;
    return -1;
  }
  for (std::size_t c = 0; c < stats.found; ++c) {
    const int a = static_cast<int>(from.point_to_patch[scratch.idx[c]]);
    if (inChosen(a)) continue;
    const PreparedFeatureSet& qa = from.sets[static_cast<std::size_t>(a)];
    const double denom = static_cast<double>(qb.size() + qa.size());
    const double d = featureSetDistance(qb, qa, p.match, p.costs, tieSafeBound(best_hat, denom), scratch.distance);
    ++compared;
    if (d == kExceedsBound) {
      ++stats.cut;
      continue;
    }
    if (better(d / denom, a, best_hat, best)) {
      best = -1;  // b prefers a patch that did not choose it
      break;
    }
  }
  stats.found = compared;
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

  const auto t_tree = std::chrono::steady_clock::now();
  SearchIndex ia, ib;
  buildIndex(qb, p, true, ib);
  buildIndex(qa, p, p.mutual_check, ia);
  r.stats.tree_ms = msSince(t_tree);

  const auto t_match = std::chrono::steady_clock::now();
  tbb::enumerable_thread_specific<SearchScratch> scratch;
  std::vector<std::uint32_t> all_a;
  for (std::size_t i = 0; i < qa.size(); ++i)
    if (!qa[i].empty()) all_a.push_back(static_cast<std::uint32_t>(i));
  std::vector<SearchOutcome> a_to_b(all_a.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, all_a.size(), 8), [&](const tbb::blocked_range<std::size_t>& range) {
    auto& s = scratch.local();
    for (std::size_t k = range.begin(); k != range.end(); ++k) a_to_b[k] = searchBest(ia, all_a[k], ib, p, s);
  });
  for (const auto& o : a_to_b) {
    r.stats.comparisons += o.found;
    r.stats.cut_early += o.cut;
    r.stats.gated_out += o.best < 0 && o.found > 0 && !o.ambiguous;
    r.stats.ambiguous += o.ambiguous;
  }

  // Mutual check (B -> A) only for the patches of B chosen by some patch of A.
  std::vector<int> b_to_a(qb.size(), -1);
  if (p.mutual_check) {
    // Choosers of each b, ascending (counting sort).
    std::vector<std::uint32_t> offset(qb.size() + 1, 0);
    for (const auto& o : a_to_b)
      if (o.best >= 0) ++offset[static_cast<std::size_t>(o.best) + 1];
    for (std::size_t j = 0; j < qb.size(); ++j) offset[j + 1] += offset[j];
    std::vector<std::uint32_t> choosers(offset.back()), fill(offset.begin(), offset.end() - 1);
    std::vector<std::uint32_t> which;
    for (std::size_t k = 0; k < all_a.size(); ++k)
      if (a_to_b[k].best >= 0) choosers[fill[static_cast<std::size_t>(a_to_b[k].best)]++] = all_a[k];
    for (std::size_t j = 0; j < qb.size(); ++j)
      if (offset[j + 1] > offset[j]) which.push_back(static_cast<std::uint32_t>(j));
    std::vector<SearchOutcome> back(which.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, which.size(), 4), [&](const tbb::blocked_range<std::size_t>& range) {
      auto& s = scratch.local();
      for (std::size_t k = range.begin(); k != range.end(); ++k) {
        const std::uint32_t j = which[k];
        back[k].best = mutualPartner(ia, ib, j, choosers.data() + offset[j], offset[j + 1] - offset[j], p, s, back[k]);
      }
    });
    for (std::size_t k = 0; k < which.size(); ++k) {
      b_to_a[which[k]] = back[k].best;
      r.stats.comparisons += back[k].found;
      r.stats.cut_early += back[k].cut;
    }
  }
  for (std::size_t k = 0; k < all_a.size(); ++k) {
    const auto& o = a_to_b[k];
    if (o.best < 0) continue;
    const int a = static_cast<int>(all_a[k]);
    if (p.mutual_check && b_to_a[static_cast<std::size_t>(o.best)] != a) {
      ++r.stats.not_mutual;
      r.one_way.push_back({a, o.best, o.best_hat});
      continue;
    }
    r.associations.push_back({a, o.best, o.best_hat});
  }
  r.stats.matching_ms = msSince(t_match);
  if (r.associations.empty())
    r.reason = r.one_way.empty() ? "no candidate within the gating distance lambda"
                                 : "every best partner was dropped by the mutual check (they are in one_way)";
  return r;
}

AssociationResult associateViews(const std::vector<PatchGeometry>& a, const std::vector<PatchGeometry>& b,
                                 const AssociationParams& p) {
  validate(p);
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<std::vector<Feature>> qa, qb;
  tbb::parallel_invoke([&] { qa = computeFeatureSets(a, p.feature_sets); },
                       [&] { qb = computeFeatureSets(b, p.feature_sets); });
  const double features_ms = msSince(t0);
  AssociationResult r = associateFeatureSets(qa, qb, p);
  r.stats.features_ms = features_ms;
  return r;
}

}  // namespace gasp
