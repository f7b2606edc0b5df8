// Restricted Damerau-Levenshtein (OSA) distance: equals an obviously-correct full-matrix
// reference, symmetric, zero on identical input; early termination never changes an accepted
// result; the paper's sanity case; feature sequences with the non-transitive Match().
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "gasp/association/edit_distance.h"
#include "gasp/association/feature_match.h"
#include "gasp/association/feature_ordering.h"
#include "gasp/core/error.h"

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// Textbook full-matrix OSA (NOTES item 4), no rolling rows, no early exit.
template <class Seq, class MatchFn>
double referenceOsa(const Seq& a, const Seq& b, MatchFn match, const gasp::EditCosts& c) {
  const std::size_t n = a.size(), m = b.size();
  std::vector<std::vector<double>> t(n + 1, std::vector<double>(m + 1, 0.0));
  for (std::size_t i = 0; i <= n; ++i) t[i][0] = static_cast<double>(i) * c.del;
  for (std::size_t j = 0; j <= m; ++j) t[0][j] = static_cast<double>(j) * c.insert;
  for (std::size_t i = 1; i <= n; ++i) {
    for (std::size_t j = 1; j <= m; ++j) {
      const bool same = match(a[i - 1], b[j - 1]);
      t[i][j] = std::min({t[i - 1][j] + c.del, t[i][j - 1] + c.insert,
                          t[i - 1][j - 1] + (same ? 0.0 : c.replace)});
      if (i > 1 && j > 1 && match(a[i - 1], b[j - 2]) && match(a[i - 2], b[j - 1])) {
        t[i][j] = std::min(t[i][j], t[i - 2][j - 2] + c.transpose);
      }
    }
  }
  return t[n][m];
}

const auto kCharEq = [](char x, char y) { return x == y; };

gasp::EditCosts unitCosts() {
  gasp::EditCosts c;
  c.replace = 1.0;
  c.transpose = 1.0;
  return c;
}

std::string randomString(std::mt19937& rng, std::size_t max_len, int alphabet) {
  std::uniform_int_distribution<std::size_t> len(0, max_len);
  std::uniform_int_distribution<int> ch(0, alphabet - 1);
  std::string s(len(rng), 'a');
  for (auto& x : s) x = static_cast<char>('a' + ch(rng));
  return s;
}

/// b = a with random adjacent swaps, deletions and insertions (so transpositions occur).
std::string perturb(const std::string& a, std::mt19937& rng, int alphabet) {
  std::string b = a;
  std::uniform_real_distribution<double> p(0.0, 1.0);
  std::uniform_int_distribution<int> ch(0, alphabet - 1);
  for (std::size_t i = 0; i + 1 < b.size(); ++i) {
    if (p(rng) < 0.2) std::swap(b[i], b[i + 1]);
  }
  std::string out;
  for (char x : b) {
    const double r = p(rng);
    if (r < 0.1) continue;
    out.push_back(x);
    if (r > 0.9) out.push_back(static_cast<char>('a' + ch(rng)));
  }
  return out;
}

}  // namespace

TEST(EditDistance, PaperSanityCase) {
  const gasp::EditCosts osa = unitCosts();
  gasp::EditCosts lev = unitCosts();
  lev.transpose = kInf;  // no transpositions: plain Levenshtein
  EXPECT_EQ(gasp::osaDistance(std::string("ABCD"), std::string("BAC"), kCharEq, osa), 2.0);
  EXPECT_EQ(gasp::osaDistance(std::string("ABCD"), std::string("BAC"), kCharEq, lev), 3.0);
  EXPECT_EQ(referenceOsa(std::string("ABCD"), std::string("BAC"), kCharEq, osa), 2.0);
  EXPECT_EQ(referenceOsa(std::string("ABCD"), std::string("BAC"), kCharEq, lev), 3.0);
  // OSA is restricted: "CA" -> "ABC" is 3 (true Damerau-Levenshtein would give 2).
  EXPECT_EQ(gasp::osaDistance(std::string("CA"), std::string("ABC"), kCharEq, osa), 3.0);
}

TEST(EditDistance, DefaultCostsKnownValues) {
  const gasp::EditCosts c;  // insert = delete = 1, replace = inf, transpose = 0
  EXPECT_EQ(gasp::osaDistance(std::string("ABCD"), std::string("BAC"), kCharEq, c), 1.0);
  EXPECT_EQ(gasp::osaDistance(std::string("AB"), std::string("BA"), kCharEq, c), 0.0);
  EXPECT_EQ(gasp::osaDistance(std::string("AB"), std::string("CD"), kCharEq, c), 4.0);  // no replace
  EXPECT_EQ(gasp::osaDistance(std::string(""), std::string("xyz"), kCharEq, c), 3.0);
  EXPECT_EQ(gasp::osaDistance(std::string("xy"), std::string(""), kCharEq, c), 2.0);
  EXPECT_EQ(gasp::osaDistance(std::string(""), std::string(""), kCharEq, c), 0.0);
}

TEST(EditDistance, EqualsReferenceOnRandomStrings) {
  std::mt19937 rng(12345);
  gasp::EditDistanceWorkspace ws;
  gasp::EditCosts asym;  // asymmetric costs exercise the insert/delete convention
  asym.insert = 1.5;
  asym.del = 0.5;
  asym.replace = 1.25;
  asym.transpose = 0.75;
  const std::vector<gasp::EditCosts> costs = {gasp::EditCosts{}, unitCosts(), asym};
  int checked = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const int alphabet = 2 + trial % 5;
    const std::string a = randomString(rng, 14, alphabet);
    const std::string b = trial % 2 ? perturb(a, rng, alphabet) : randomString(rng, 14, alphabet);
    for (const auto& c : costs) {
      const double ref = referenceOsa(a, b, kCharEq, c);
      ASSERT_EQ(gasp::osaDistance(a, b, kCharEq, c, kInf, ws), ref) << a << " / " << b;
      ++checked;
    }
  }
  EXPECT_EQ(checked, 9000);
}

TEST(EditDistance, SymmetricAndZeroOnIdentical) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 2000; ++trial) {
    const std::string a = randomString(rng, 20, 4);
    const std::string b = perturb(a, rng, 4);
    for (const auto& c : {gasp::EditCosts{}, unitCosts()}) {
      EXPECT_EQ(gasp::osaDistance(a, b, kCharEq, c), gasp::osaDistance(b, a, kCharEq, c));
      EXPECT_EQ(gasp::osaDistance(a, a, kCharEq, c), 0.0);
    }
  }
}

TEST(EditDistance, EarlyTerminationNeverChangesAnAcceptedResult) {
  std::mt19937 rng(99);
  gasp::EditDistanceWorkspace ws;
  std::uniform_real_distribution<double> frac(-0.1, 1.1);
  int accepted = 0, rejected = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const int alphabet = 2 + trial % 4;
    const std::string a = randomString(rng, 25, alphabet);
    const std::string b = trial % 3 ? perturb(a, rng, alphabet) : randomString(rng, 25, alphabet);
    const gasp::EditCosts c = trial % 2 ? gasp::EditCosts{} : unitCosts();
    const double truth = referenceOsa(a, b, kCharEq, c);
    // Bounds around the true distance, including exactly it and integers next to it.
    for (const double bound : {truth, truth - 1.0, truth + 1.0, truth - 0.5,
                               frac(rng) * static_cast<double>(a.size() + b.size())}) {
      const double d = gasp::osaDistance(a, b, kCharEq, c, bound, ws);
      if (truth <= bound) {
        ASSERT_EQ(d, truth) << a << " / " << b << " bound " << bound;
        ++accepted;
      } else {
        ASSERT_EQ(d, gasp::kExceedsBound) << a << " / " << b << " bound " << bound;
        ++rejected;
      }
    }
  }
  EXPECT_GT(accepted, 1000);
  EXPECT_GT(rejected, 1000);
}

TEST(EditDistance, FeatureSequencesEqualReference) {
  // Features on a coarse grid so that Match() (non-transitive) fires often and transpositions
  // occur; sequences sorted like the pipeline sorts them.
  std::mt19937 rng(2024);
  std::uniform_int_distribution<int> grid(0, 3);
  const gasp::MatchParams mp;
  const gasp::FeatureMatch match{mp};
  gasp::EditDistanceWorkspace ws;
  for (int trial = 0; trial < 1500; ++trial) {
    std::vector<gasp::Feature> a, b;
    for (auto* s : {&a, &b}) {
      const int len = grid(rng) * 4;
      for (int i = 0; i < len; ++i) {
        gasp::Feature q{};
        for (std::size_t d = 0; d < 7; ++d) {
          const double step = d < 4 ? 0.03 : 0.12;  // within/outside r_dev, theta_dev
          q[d] = step * (d == 0 ? grid(rng) : grid(rng) % 2);
        }
        s->push_back(q);
      }
      gasp::sortFeatures(*s);
    }
    for (const auto& c : {gasp::EditCosts{}, unitCosts()}) {
      const double ref = referenceOsa(a, b, match, c);
      ASSERT_EQ(gasp::osaDistance(a, b, match, c, kInf, ws), ref);
      ASSERT_EQ(gasp::osaDistance(b, a, match, c, kInf, ws), ref);
      ASSERT_EQ(gasp::osaDistance(a, b, match, c, ref, ws), ref);
      if (ref > 0) {
        ASSERT_EQ(gasp::osaDistance(a, b, match, c, ref - 1.0, ws), gasp::kExceedsBound);
      }
    }
  }
}

TEST(EditDistance, NormalisedDistanceAndBound) {
  EXPECT_DOUBLE_EQ(gasp::normalisedDistance(30.0, 40, 60), 0.3);
  EXPECT_DOUBLE_EQ(gasp::normalisedDistance(100.0, 40, 60), 1.0);
  EXPECT_TRUE(std::isinf(gasp::normalisedDistance(0.0, 0, 0)));
  EXPECT_DOUBLE_EQ(gasp::distanceBound(0.65, 40, 60), 65.0);
  EXPECT_THROW(gasp::distanceBound(1.5, 1, 1), gasp::Error);
  EXPECT_THROW(gasp::distanceBound(std::nan(""), 1, 1), gasp::Error);
}

TEST(EditDistance, InvalidCostsThrow) {
  gasp::EditCosts c;
  c.insert = 0.0;
  EXPECT_THROW(gasp::osaDistance(std::string("a"), std::string("b"), kCharEq, c), gasp::Error);
  c = gasp::EditCosts{};
  c.del = kInf;
  EXPECT_THROW(gasp::osaDistance(std::string("a"), std::string("b"), kCharEq, c), gasp::Error);
  c = gasp::EditCosts{};
  c.transpose = -1.0;
  EXPECT_THROW(gasp::osaDistance(std::string("a"), std::string("b"), kCharEq, c), gasp::Error);
  c = gasp::EditCosts{};
  c.replace = std::nan("");
  EXPECT_THROW(gasp::osaDistance(std::string("a"), std::string("b"), kCharEq, c), gasp::Error);
  EXPECT_THROW(gasp::osaDistance(std::string("a"), std::string("b"), kCharEq, gasp::EditCosts{},
                                 std::nan("")),
               gasp::Error);
}

// Timing is printed, never asserted (speed is measured in benchmarks/bench_edit_distance.cpp).
TEST(EditDistance, PrintsTimingOfFullViewSizedSets) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> dist(0.05, 3.0), ang(0.0, 3.14159);
  std::uniform_int_distribution<int> sgn(-1, 1);
  const auto make = [&](std::size_t n) {
    std::vector<gasp::Feature> s(n);
    for (auto& q : s) {
      const double r = dist(rng);
      q = {r * sgn(rng), r * sgn(rng), r * sgn(rng), r, ang(rng), ang(rng), ang(rng)};
    }
    gasp::sortFeatures(s);
    return s;
  };
  const auto a = make(750), b = make(750);
  const gasp::FeatureMatch match{gasp::MatchParams{}};
  gasp::EditDistanceWorkspace ws;
  const int reps = 20;
  double sink = 0.0;
  auto t0 = std::chrono::steady_clock::now();
  for (int i = 0; i < reps; ++i) sink += gasp::osaDistance(a, b, match, gasp::EditCosts{}, kInf, ws);
  auto t1 = std::chrono::steady_clock::now();
  const double bound = gasp::distanceBound(0.65, a.size(), b.size());
  double sink2 = 0.0;
  for (int i = 0; i < reps; ++i) sink2 += gasp::osaDistance(a, b, match, gasp::EditCosts{}, bound, ws);
  auto t2 = std::chrono::steady_clock::now();
  const auto ms = [](auto d) { return std::chrono::duration<double, std::milli>(d).count(); };
  std::printf("750 x 750 features: %.3f ms per full DP (distance %.0f), %.3f ms with bound %.1f\n",
              ms(t1 - t0) / reps, sink / reps, ms(t2 - t1) / reps, bound);
  EXPECT_GT(sink, 0.0);
  EXPECT_TRUE(std::isinf(sink2));  // unrelated random sets exceed lambda = 0.65
}
