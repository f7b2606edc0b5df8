#pragma once
/// \file feature_ordering.h Tolerant lexicographic ordering of a feature set Q_mu (paper section
/// III-C, NOTES item 3) that is a strict weak ordering, so std::sort may use it.
///
/// The paper orders features lexicographically, "dimension 1 decides unless equal within
/// tolerance". Equality within a tolerance is not transitive (a ~ b, b ~ c, a !~ c), so that
/// comparator is not a strict weak ordering and std::sort with it is undefined behaviour.
/// Here each component is quantised into bins of the tolerance width, key_i = floor(q_i / tol_i),
/// and keys are compared lexicographically. Two values in the same bin are "equal within
/// tolerance" (their difference is < tol), and equality of keys is an equivalence relation, so the
/// order is a strict weak ordering. The price: two values closer than tol but on either side of
/// a bin border compare as different. The matching stage absorbs it: Match() accepts deviations up
/// to r_dev / theta_dev (2 x the ordering tolerance in the paper), and an element displaced by the
/// bin border usually only swaps with a neighbour in the sequence, which the restricted
/// Damerau-Levenshtein distance pays with the transposition cost (0 by default).
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "gasp/association/invariant_feature.h"

namespace gasp {

/// Tolerances of the ordering (paper, Kinect: e_r = 0.02 m, e_theta = 5 deg).
struct OrderingParams {
  double e_r_m = 0.02;                                   ///< bin width of components 0..3 [m]
  double e_theta_rad = 5.0 * 3.14159265358979323846 / 180.0;  ///< bin width of components 4..6 [rad]
};

/// Throws gasp::Error unless both tolerances are finite and > 0.
void validate(const OrderingParams& params);

/// Quantised feature: key_i = floor(q_i / tol_i) (saturated to +-2^62; NaN sorts last).
using FeatureKey = std::array<std::int64_t, 7>;

/// The quantised key of q.
FeatureKey quantise(const Feature& q, const OrderingParams& params);

namespace detail {
/// floor(scaled), saturated to +-2^62; NaN gives 2^62 + 1 (after every finite value).
inline std::int64_t floorKey(double scaled) {
  constexpr double kKeyLimit = 4611686018427387904.0;  // 2^62, exactly representable
  if (std::isnan(scaled)) return static_cast<std::int64_t>(kKeyLimit) + 1;
  const double b = std::floor(scaled);
  if (b >= kKeyLimit) return static_cast<std::int64_t>(kKeyLimit);
  if (b <= -kKeyLimit) return -static_cast<std::int64_t>(kKeyLimit);
  return static_cast<std::int64_t>(b);
}
}  // namespace detail

/// One component of the key: floor(value / tol) with the saturation and NaN rule of quantise()
/// (quantise(q, p)[i] == quantiseComponent(q[i], tol_i)). Non-decreasing in value for tol > 0.
inline std::int64_t quantiseComponent(double value, double tol) { return detail::floorKey(value / tol); }

/// The tolerant comparator: a < b iff quantise(a) < quantise(b) lexicographically. A strict weak
/// ordering; a and b are equivalent iff all components share a bin.
struct TolerantFeatureLess {
  OrderingParams params;
  bool operator()(const Feature& a, const Feature& b) const {
    return quantise(a, params) < quantise(b, params);
  }
};

/// Sorts Q_mu in place by TolerantFeatureLess, ties (same key) broken by the exact values
/// (lexicographic), so the result does not depend on the input order (deterministic). Keys are
/// computed once per feature. Validates params.
void sortFeatures(std::vector<Feature>& features, const OrderingParams& params = {});

}  // namespace gasp
