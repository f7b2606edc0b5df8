#pragma once
/// \file banded_distance.h Fast exact D_RDL between feature sets (paper III-D): the same value as
/// osaDistance() with FeatureMatch, computed on the few cells that can match.
///
/// Why it is exact and fast (docs/association.md, section 4):
///  * Gain form. With replace >= insert + delete (the paper's replace = infinity), a replacement
///    is never better than a deletion plus an insertion, so
///        D = del n + ins m - max G,  G = (ins + del) #matched pairs + (2 (ins + del) - transpose) #transpositions,
///    over the OSA alignments (chains of matched pairs, adjacent crossings allowed). Only the
///    cells that match matter.
///  * Band. Feature sets are sorted by their quantised keys, component 0 first (sortFeatures()),
///    and Match(q, q') needs |q0 - q0'| <= r_dev. So the elements of b that a_i can match have
///    component-0 keys in [key(q0_i - r_dev), key(q0_i + r_dev)] (a few bins wide, widened by a
///    rounding margin): one contiguous window of b per row (table lookup). Within a run of equal
///    component-0 keys the set is sorted by the component-1 key, and Match needs
///    |q1 - q1'| <= r_dev too: long runs (coplanar neighbours all have q0 = 0) are cut down to the
///    sub-run of matching component-1 keys by binary search. The match test (a float SIMD test
///    with a margin, the doubles decide near the tolerance) runs only there, on a small share of
///    the cells.
///  * Bounds before the DP: every matched pair satisfies |q_c - q'_c| <= tol_c for each component
///    c alone, so #pairs <= the maximum matching of the two value lists of component c under that
///    tolerance, which a greedy two-pointer walk over the sorted values gives exactly (O(n + m)).
///    Components 0, 2 and 4 are tried; a candidate that cannot reach the gain needed for
///    D <= bound is rejected without DP (about half of the comparisons of a search).
///  * DP. Transposition cost 0 (default) and at most 64 elements on one side (k = 30): bit-parallel,
///    one 64-bit word per row (LCS step of Hyyrö 2004 plus a correction per transposition).
///    Otherwise a sparse DP: G[i][.] is non-decreasing and row i differs from row i-1 only from
///    its matches on, so rows without a match cost nothing.
///  * Early termination as in osaDistance(): the DP stops when two consecutive rows cannot reach
///    the gain needed for D <= bound (the rows left that have a non-empty window bound the gain
///    still possible).
/// Sets that are not sorted by component-0 key fall back to full windows (still exact); costs with
/// replace < insert + delete fall back to osaDistance().
///
/// The result equals osaDistance(a, b, FeatureMatch{match}, costs, bound) exactly when the costs
/// are integers (the defaults) or dyadic fractions; otherwise up to floating-point rounding of the
/// sum (the terms are added in another order). Tested against osaDistance() on random sequences
/// (test_banded_distance.cpp).
#include <cstdint>
#include <vector>

#include "gasp/association/edit_distance.h"
#include "gasp/association/feature_match.h"
#include "gasp/association/feature_ordering.h"
#include "gasp/association/invariant_feature.h"

namespace gasp {

/// A feature set prepared for many comparisons. Filled by prepareFeatureSet(); read-only
/// afterwards (the fields depend on each other).
struct PreparedFeatureSet {
  std::vector<Feature> features;  ///< Q, in the given order
  /// Normalised copy for the fast match test: component c divided by its tolerance (r_dev or
  /// theta_dev), 8 floats per feature (the last is 0); empty unless float_safe. Exactness is kept
  /// by a margin: pairs whose float test is not clear-cut are decided on the doubles of `features`.
  std::vector<float> scaled;
  /// Each component's values sorted ascending (component c at [c size(), (c + 1) size())), for
  /// the matching bounds (and the quantile signatures of view_association.cpp); empty when a value
  /// is not finite (the bounds are then skipped).
  std::vector<double> sorted_values;
  /// Ordering keys of components 0 and 1 of each feature, and for each feature the range of keys
  /// a matching feature can have (lo > hi: matches nothing, e.g. NaN).
  std::vector<std::int64_t> key0, key0_lo, key0_hi;
  std::vector<std::int64_t> key1, key1_lo, key1_hi;
  /// End of the run of equal key0 that contains each feature (index one past its last element).
  std::vector<std::uint32_t> run_end;
  /// key0_first[k - key0_min] = first index with key0 >= k, for k in [key0_min, key0_max + 1];
  /// empty when the keys are not sorted or span too many bins (a two-pointer walk is used then).
  std::vector<std::uint32_t> key0_first;
  std::int64_t key0_min = 0;
  bool key0_sorted = false;   ///< key0 non-decreasing (the band may be used)
  bool key01_sorted = false;  ///< (key0, key1) lexicographically non-decreasing (runs may be split by key1)
  bool float_safe = false;    ///< every scaled value is finite and small enough for the float test
  std::size_t size() const { return features.size(); }
  bool empty() const { return features.empty(); }
};

/// Prepares q for featureSetDistance() below. `match` must be the MatchParams used later and
/// `ordering` those q was sorted with (any order is accepted, unsorted sets only compare slower).
/// Validates both.
PreparedFeatureSet prepareFeatureSet(const std::vector<Feature>& q, const MatchParams& match,
                                     const OrderingParams& ordering = {});

/// Scratch memory of the prepared-set featureSetDistance(); one per thread, reused.
struct BandedWorkspace {
  std::vector<double> gain;                    ///< three rows of G (sparse DP)
  std::vector<unsigned char> matches;          ///< two rows of match flags, zero outside the sub-runs (sparse DP)
  std::vector<std::uint32_t> lo, hi;           ///< window of each row, [lo, hi)
  std::vector<std::uint32_t> runs, prev_runs;  ///< sub-runs of the current / previous row (begin, end pairs)
  std::vector<std::uint32_t> usable_after;     ///< rows from i on with a non-empty window
  EditDistanceWorkspace fallback;              ///< for costs with replace < insert + delete
};

/// D_RDL(a, b) = osaDistance(a.features, b.features, FeatureMatch{match}, costs, bound) (see the
/// file comment for exactness), kExceedsBound when above `bound`. `a` and `b` must have been
/// prepared with the same `match` (not checked).
double featureSetDistance(const PreparedFeatureSet& a, const PreparedFeatureSet& b, const MatchParams& match,
                          const EditCosts& costs, double bound, BandedWorkspace& ws);

}  // namespace gasp
