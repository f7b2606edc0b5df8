// The banded, sparse D_RDL between prepared feature sets (banded_distance.h) equals osaDistance()
// with FeatureMatch exactly: random sorted sequences built to make Match fire often, long runs of
// equal component-0 keys (coplanar neighbours), values on bin borders and at exactly the match
// tolerance, transpositions, unsorted and non-finite input, all cost variants, and bounds at, just
// below and just above the distance.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "gasp/association/banded_distance.h"
#include "gasp/association/feature_sets.h"
#include "gasp/core/error.h"

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

enum class Kind { kGrid, kPlanar, kBorders, kRealistic };

/// A random feature; `kind` decides how close features are to each other and to bin borders.
gasp::Feature randomFeature(std::mt19937& rng, Kind kind) {
  std::uniform_int_distribution<int> small(0, 3), sign(-1, 1), coin(0, 1);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  gasp::Feature q{};
  switch (kind) {
    case Kind::kGrid:  // steps within / outside r_dev (0.04) and theta_dev (0.1745)
      for (std::size_t d = 0; d < 7; ++d) q[d] = (d < 4 ? 0.03 : 0.12) * (d < 2 ? small(rng) : coin(rng));
      break;
    case Kind::kPlanar: {  // mostly q0 = q2 = 0, q1 = q3 = |r| (coplanar neighbours)
      const double r = 0.05 + 0.3 * u(rng);
      const bool in_plane = u(rng) < 0.8;
      q = {in_plane ? 0.0 : r * sign(rng), r, in_plane ? 0.0 : r * sign(rng), r, 0.15 * u(rng),
           1.57 + 0.2 * (u(rng) - 0.5), 1.57 + 0.2 * (u(rng) - 0.5)};
      break;
    }
    case Kind::kBorders: {  // multiples of e_r = 0.02 and of r_dev, nudged by one ulp or not
      for (std::size_t d = 0; d < 7; ++d) {
        const double step = d < 4 ? 0.02 : 5.0 * M_PI / 180.0;
        double x = step * (small(rng) - 1);
        const int nudge = small(rng);
        if (nudge == 1) x = std::nextafter(x, kInf);
        if (nudge == 2) x = std::nextafter(x, -kInf);
        q[d] = x;
      }
      break;
    }
    case Kind::kRealistic: {
      const double r = 0.05 + 0.5 * u(rng);
      q = {r * sign(rng), r * sign(rng), r * sign(rng), r, M_PI * u(rng), M_PI * u(rng), M_PI * u(rng)};
      break;
    }
  }
  for (double& x : q) x += 0.0;
  return q;
}

std::vector<gasp::Feature> randomSet(std::mt19937& rng, Kind kind, std::size_t max_len) {
  std::uniform_int_distribution<std::size_t> len(0, max_len);
  std::vector<gasp::Feature> s(len(rng));
  for (auto& q : s) q = randomFeature(rng, kind);
  gasp::sortFeatures(s);
  return s;
}

/// b = a with its features jittered below the tolerance, some dropped, some added, and adjacent
/// swaps (so the distance is small and transpositions occur).
std::vector<gasp::Feature> perturbed(const std::vector<gasp::Feature>& a, std::mt19937& rng, Kind kind, bool resort) {
  std::uniform_real_distribution<double> u(0.0, 1.0), jr(-0.03, 0.03), ja(-0.15, 0.15);
  std::vector<gasp::Feature> b;
  for (const auto& q : a) {
    if (u(rng) < 0.1) continue;
    gasp::Feature p = q;
    if (u(rng) < 0.5) {
      for (std::size_t d = 0; d < 7; ++d) p[d] += d < 4 ? jr(rng) : ja(rng);
      if (kind == Kind::kPlanar && q[0] == 0.0) p[0] = p[2] = 0.0;
    }
    b.push_back(p);
    if (u(rng) < 0.1) b.push_back(randomFeature(rng, kind));
  }
  if (resort) gasp::sortFeatures(b);
  for (std::size_t i = 0; i + 1 < b.size(); ++i)
    if (u(rng) < 0.1) std::swap(b[i], b[i + 1]);  // out of order on purpose: transpositions
  return b;
}

gasp::EditCosts costsVariant(int v) {
  gasp::EditCosts c;  // 0: paper defaults
  switch (v) {
    case 1: c.transpose = 1.0; break;
    case 2: c.transpose = kInf; break;
    case 3: c.insert = 2.0; c.del = 1.0; c.transpose = 0.5; break;
    case 4: c.insert = 1.5; c.del = 0.5; c.transpose = 0.75; c.replace = 2.0; break;  // replace = ins + del
    case 5: c.replace = 1.0; c.transpose = 1.0; break;  // replace useful: falls back to osaDistance
    default: break;
  }
  return c;
}

/// Checks featureSetDistance() against osaDistance() for one pair under all cost variants and a
/// set of bounds; returns the number of comparisons made.
int checkPair(const std::vector<gasp::Feature>& a, const std::vector<gasp::Feature>& b, const gasp::MatchParams& mp,
              std::mt19937& rng, gasp::BandedWorkspace& ws) {
  const auto pa = gasp::prepareFeatureSet(a, mp), pb = gasp::prepareFeatureSet(b, mp);
  const gasp::FeatureMatch match{mp};
  std::uniform_real_distribution<double> frac(0.0, 1.0);
  int checked = 0;
  for (int v = 0; v < 6; ++v) {
    const gasp::EditCosts c = costsVariant(v);
    const double truth = gasp::osaDistance(a, b, match, c);
    const double total = static_cast<double>(a.size()) * c.del + static_cast<double>(b.size()) * c.insert;
    for (const double bound : {kInf, truth, truth - 1.0, truth - 0.25, truth + 0.5, frac(rng) * total,
                               0.5 * total, 0.0}) {
      const double expected = truth <= bound ? truth : gasp::kExceedsBound;
      EXPECT_EQ(gasp::featureSetDistance(pa, pb, mp, c, bound, ws), expected)
          << "costs variant " << v << ", bound " << bound << ", sizes " << a.size() << " x " << b.size();
      EXPECT_EQ(gasp::featureSetDistance(pb, pa, mp, c, bound, ws),
                gasp::osaDistance(b, a, match, c, bound));
      ++checked;
    }
  }
  return checked;
}

}  // namespace

TEST(BandedDistance, EqualsOsaDistanceOnRandomSortedSequences) {
  std::mt19937 rng(31337);
  gasp::BandedWorkspace ws;  // reused across sizes on purpose
  const gasp::MatchParams mp;
  int checked = 0;
  for (int trial = 0; trial < 1200; ++trial) {
    const Kind kind = static_cast<Kind>(trial % 4);
    const std::size_t max_len = trial % 10 == 0 ? 90 : 35;
    const auto a = randomSet(rng, kind, max_len);
    const auto b = trial % 3 == 0 ? randomSet(rng, kind, max_len) : perturbed(a, rng, kind, trial % 3 == 1);
    checked += checkPair(a, b, mp, rng, ws);
    if (::testing::Test::HasFailure()) return;
  }
  EXPECT_GT(checked, 50000);
}

TEST(BandedDistance, OtherTolerancesAndOrderings) {
  std::mt19937 rng(4242);
  gasp::BandedWorkspace ws;
  for (int trial = 0; trial < 300; ++trial) {
    gasp::MatchParams mp;
    gasp::OrderingParams op;
    switch (trial % 4) {
      case 0: mp.r_dev_m = 0.0; mp.theta_dev_rad = 0.0; break;  // exact equality, no float test
      case 1: mp.r_dev_m = 0.1; op.e_r_m = 0.01; break;           // wide band, fine bins
      case 2: mp.r_dev_m = 0.005; op.e_r_m = 0.05; break;         // band narrower than a bin
      default: break;
    }
    const Kind kind = static_cast<Kind>(trial % 3);
    std::vector<gasp::Feature> a = randomSet(rng, kind, 30);
    gasp::sortFeatures(a, op);
    std::vector<gasp::Feature> b = perturbed(a, rng, kind, false);
    gasp::sortFeatures(b, op);
    if (trial % 5 == 0 && !b.empty()) b.push_back(b.front());  // duplicates
    const auto pa = gasp::prepareFeatureSet(a, mp, op), pb = gasp::prepareFeatureSet(b, mp, op);
    const gasp::FeatureMatch match{mp};
    for (const double bound : {kInf, 10.0, 3.0}) {
      ASSERT_EQ(gasp::featureSetDistance(pa, pb, mp, gasp::EditCosts{}, bound, ws),
                gasp::osaDistance(a, b, match, gasp::EditCosts{}, bound))
          << "trial " << trial;
    }
  }
}

TEST(BandedDistance, UnsortedAndNonFiniteInputStayExact) {
  std::mt19937 rng(77);
  gasp::BandedWorkspace ws;
  const gasp::MatchParams mp;
  const gasp::FeatureMatch match{mp};
  for (int trial = 0; trial < 400; ++trial) {
    auto a = randomSet(rng, Kind::kGrid, 25);
    auto b = perturbed(a, rng, Kind::kGrid, trial % 2 == 0);
    std::shuffle(b.begin(), b.end(), rng);  // not sorted: no band
    if (trial % 3 == 0 && !a.empty()) a[a.size() / 2][trial % 7] = std::nan("");
    if (trial % 4 == 0 && !b.empty()) b[0][trial % 7] = (trial % 8 == 0 ? kInf : -kInf);
    if (trial % 5 == 0 && !a.empty()) a[0][0] = 1e6;  // not float-safe: doubles only
    const auto pa = gasp::prepareFeatureSet(a, mp), pb = gasp::prepareFeatureSet(b, mp);
    for (const double bound : {kInf, 5.0, 1.0}) {
      ASSERT_EQ(gasp::featureSetDistance(pa, pb, mp, gasp::EditCosts{}, bound, ws),
                gasp::osaDistance(a, b, match, gasp::EditCosts{}, bound))
          << "trial " << trial;
    }
  }
}

TEST(BandedDistance, SetsOfAViewAgainstEachOther) {
  // Feature sets of real geometry (random patches, k nearest), every pair, bound as the search
  // uses it.
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> pos(-1.0, 1.0);
  std::normal_distribution<double> gn(0.0, 1.0);
  std::vector<gasp::PatchGeometry> patches(120);
  for (std::size_t i = 0; i < patches.size(); ++i) {
    auto& p = patches[i];
    // Half on a floor plane (coplanar: long component-0 runs), half scattered.
    p.centroid = i % 2 ? Eigen::Vector3d(pos(rng), 1.0, 2.0 + pos(rng)) : Eigen::Vector3d(pos(rng), pos(rng), 2.0 + pos(rng));
    p.normal = i % 2 ? Eigen::Vector3d(0, -1, 0) : Eigen::Vector3d(gn(rng), gn(rng), gn(rng)).normalized();
  }
  gasp::FeatureSetParams fp;
  fp.neighbourhood.k = 20;
  const auto sets = gasp::computeFeatureSets(patches, fp);
  gasp::MatchParams mp;
  std::vector<gasp::PreparedFeatureSet> prepared;
  for (const auto& s : sets) prepared.push_back(gasp::prepareFeatureSet(s, mp));
  gasp::BandedWorkspace ws;
  const gasp::FeatureMatch match{mp};
  int finite = 0;
  for (std::size_t i = 0; i < sets.size(); ++i) {
    for (std::size_t j = 0; j < sets.size(); j += 3) {
      for (const double lambda : {1.0, 0.65, 0.3}) {
        const double bound = gasp::distanceBound(lambda, sets[i].size(), sets[j].size());
        const double d = gasp::featureSetDistance(prepared[i], prepared[j], mp, gasp::EditCosts{}, bound, ws);
        ASSERT_EQ(d, gasp::osaDistance(sets[i], sets[j], match, gasp::EditCosts{}, bound)) << i << " " << j;
        finite += d != gasp::kExceedsBound;
      }
    }
  }
  EXPECT_GT(finite, 100);
}

TEST(BandedDistance, PreparedSetFlags) {
  const gasp::MatchParams mp;
  std::vector<gasp::Feature> s = {{0.1, 0.2, 0, 0.3, 1, 1, 1}, {0.0, 0.0, 0, 0.1, 1, 1, 1}};
  auto p = gasp::prepareFeatureSet(s, mp);
  EXPECT_FALSE(p.key0_sorted);  // not in ordering order
  gasp::sortFeatures(s);
  p = gasp::prepareFeatureSet(s, mp);
  EXPECT_TRUE(p.key0_sorted);
  EXPECT_TRUE(p.key01_sorted);
  EXPECT_TRUE(p.float_safe);
  EXPECT_EQ(p.key0_lo[0], -3);  // floor((0 - 0.04 - eps) / 0.02)
  EXPECT_EQ(p.key0_hi[0], 2);   // floor((0 + 0.04 + eps) / 0.02)
  s[0][4] = std::nan("");
  p = gasp::prepareFeatureSet(s, mp);
  EXPECT_TRUE(p.sorted_values.empty());  // no matching bounds on non-finite input
  EXPECT_FALSE(p.float_safe);
  gasp::MatchParams bad;
  bad.r_dev_m = -1;
  EXPECT_THROW(gasp::prepareFeatureSet(s, bad), gasp::Error);
  gasp::BandedWorkspace ws;
  EXPECT_THROW(gasp::featureSetDistance(p, p, mp, gasp::EditCosts{}, std::nan(""), ws), gasp::Error);
}
