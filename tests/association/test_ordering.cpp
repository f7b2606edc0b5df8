// The tolerant ordering of feature sets (NOTES item 3) is a strict weak ordering, is tolerant,
// and sorting with it is deterministic.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "gasp/association/feature_ordering.h"
#include "gasp/core/error.h"

namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

/// Features that often share bins, straddle bin borders and tie in leading components.
std::vector<gasp::Feature> trickyFeatures(std::mt19937& rng, std::size_t n) {
  const gasp::OrderingParams p;
  std::uniform_int_distribution<int> lead_bin(-1, 1), bin(0, 1);  // few bins: many ties
  std::uniform_int_distribution<int> offset_kind(0, 4);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<gasp::Feature> out(n);
  for (auto& q : out) {
    for (std::size_t d = 0; d < 7; ++d) {
      const double tol = d < 4 ? p.e_r_m : p.e_theta_rad;
      const double offsets[] = {0.0, 1e-13, 0.5, 1.0 - 1e-13, unit(rng)};
      q[d] = tol * ((d < 2 ? lead_bin(rng) : bin(rng)) + offsets[offset_kind(rng)]);
    }
  }
  return out;
}

}  // namespace

TEST(FeatureOrdering, IsAStrictWeakOrdering) {
  std::mt19937 rng(31);
  const gasp::TolerantFeatureLess less{gasp::OrderingParams{}};
  const auto f = trickyFeatures(rng, 110);
  const auto equiv = [&](const gasp::Feature& a, const gasp::Feature& b) { return !less(a, b) && !less(b, a); };
  std::size_t equivalent_pairs = 0;
  for (const auto& a : f) {
    EXPECT_FALSE(less(a, a));  // irreflexive
    for (const auto& b : f) {
      if (less(a, b)) {
        EXPECT_FALSE(less(b, a));  // asymmetric
      }
      if (&a != &b && equiv(a, b)) ++equivalent_pairs;
      for (const auto& c : f) {
        if (less(a, b) && less(b, c)) {
          ASSERT_TRUE(less(a, c));  // transitive
        }
        if (equiv(a, b) && equiv(b, c)) {
          ASSERT_TRUE(equiv(a, c));  // incomparability transitive
        }
      }
    }
  }
  EXPECT_GT(equivalent_pairs, 0u);  // the data does exercise ties
}

TEST(FeatureOrdering, IsTolerantWithinABin) {
  const gasp::OrderingParams p;
  const gasp::TolerantFeatureLess less{p};
  const gasp::Feature a{0.101, 0, 0, 0.101, 12 * kDeg, 22 * kDeg, 32 * kDeg};
  gasp::Feature b = a;
  b[0] = 0.119;  // same 2 cm bin [0.10, 0.12): equal within tolerance, later dimensions decide
  b[4] = 9 * kDeg;  // bin 1 < bin 2
  EXPECT_TRUE(less(b, a));
  b[4] = a[4] + 1 * kDeg;  // same 5 deg bin as well: equivalent
  EXPECT_FALSE(less(a, b));
  EXPECT_FALSE(less(b, a));
  b[0] = 0.121;  // next bin: dimension 0 decides
  b[4] = 0.0;
  EXPECT_TRUE(less(a, b));
  // The naive "equal within tolerance" comparator would call 0.000 ~ 0.015 ~ 0.030 but
  // 0.000 < 0.030 (not transitive); the keys are consistent.
  const gasp::Feature x{0.000, 0, 0, 0, 0, 0, 0}, y{0.015, 0, 0, 0, 0, 0, 0}, z{0.030, 0, 0, 0, 0, 0, 0};
  EXPECT_FALSE(less(x, y) || less(y, x));
  EXPECT_TRUE(less(y, z));
  EXPECT_TRUE(less(x, z));
  EXPECT_EQ(gasp::quantise({-0.001, 0.0, 0.039, 0.04, 4.9 * kDeg, 5.1 * kDeg, -0.1}, p),
            (gasp::FeatureKey{-1, 0, 1, 2, 0, 1, -2}));
}

TEST(FeatureOrdering, SortingIsDeterministic) {
  std::mt19937 rng(77);
  const gasp::OrderingParams p;
  const gasp::TolerantFeatureLess less{p};
  for (int trial = 0; trial < 50; ++trial) {
    const auto f = trickyFeatures(rng, 300);
    auto ref = f;
    gasp::sortFeatures(ref, p);
    EXPECT_TRUE(std::is_sorted(ref.begin(), ref.end(), less));
    auto ref_std = f;
    std::sort(ref_std.begin(), ref_std.end(), less);
    for (int shuffle = 0; shuffle < 5; ++shuffle) {
      auto g = f;
      std::shuffle(g.begin(), g.end(), rng);
      auto h = g;
      gasp::sortFeatures(g, p);
      ASSERT_EQ(g, ref);  // identical sequence, whatever the input order
      std::sort(h.begin(), h.end(), less);  // plain std::sort: identical sequence of keys
      ASSERT_EQ(h.size(), ref_std.size());
      for (std::size_t i = 0; i < h.size(); ++i) {
        ASSERT_EQ(gasp::quantise(h[i], p), gasp::quantise(ref_std[i], p));
      }
    }
  }
}

TEST(FeatureOrdering, EmptyAndInvalid) {
  std::vector<gasp::Feature> empty;
  EXPECT_NO_THROW(gasp::sortFeatures(empty));
  EXPECT_TRUE(empty.empty());
  gasp::OrderingParams p;
  p.e_r_m = 0.0;
  EXPECT_THROW(gasp::validate(p), gasp::Error);
  EXPECT_THROW(gasp::sortFeatures(empty, p), gasp::Error);
  p = gasp::OrderingParams{};
  p.e_theta_rad = std::nan("");
  EXPECT_THROW(gasp::validate(p), gasp::Error);
}
