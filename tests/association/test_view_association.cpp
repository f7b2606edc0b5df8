// The association of two views (paper III-E): exact on noise-free rigid copies, empty with a
// reason on bad input.
#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "gasp/association/view_association.h"
#include "gasp/core/error.h"
#include "patch_motion.h"
#include "gasp/core/pose.h"

namespace {

using gasp::test::moved;
using gasp::test::randomPatches;

/// b = a moved by T, with centroid noise (sigma_m) and normal noise, some patches dropped and some
/// random ones added: distances are neither all zero nor all large, and ties occur.
std::vector<gasp::PatchGeometry> noisyView(const std::vector<gasp::PatchGeometry>& a, const gasp::Isometry3& T,
                                           double sigma_m, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> g(0.0, 1.0);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<gasp::PatchGeometry> out;
  for (const auto& p : a) {
    if (u(rng) < 0.15) continue;
    gasp::PatchGeometry q;
    q.centroid = T * p.centroid + sigma_m * Eigen::Vector3d(g(rng), g(rng), g(rng));
    q.normal = (T.linear() * p.normal + 0.05 * Eigen::Vector3d(g(rng), g(rng), g(rng))).normalized();
    out.push_back(q);
    if (u(rng) < 0.1) out.push_back(randomPatches(1, seed + static_cast<unsigned>(out.size()))[0]);
  }
  return out;
}

constexpr double kInf = std::numeric_limits<double>::infinity();

/// Patches on a regular floor grid and a wall grid (interior patches have identical neighbourhoods:
/// exact ties between candidates, and many patches preferring the same partner) plus a few
/// scattered ones.
std::vector<gasp::PatchGeometry> gridScene(unsigned seed) {
  std::vector<gasp::PatchGeometry> out;
  for (int i = 0; i < 9; ++i)
    for (int j = 0; j < 7; ++j) out.push_back({Eigen::Vector3d(-0.4 + 0.1 * i, 0.8, 1.5 + 0.1 * j), Eigen::Vector3d(0, -1, 0)});
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) out.push_back({Eigen::Vector3d(-0.3 + 0.12 * i, 0.7 - 0.12 * j, 2.3), Eigen::Vector3d(0, 0, -1)});
  const auto extra = randomPatches(15, seed);
  out.insert(out.end(), extra.begin(), extra.end());
  return out;
}

/// The specification of associateFeatureSets() when every patch is a candidate: for each a, the
/// least (D_hat, b) over all b with D_hat <= lambda (D from osaDistance() with FeatureMatch); with
/// the mutual check, kept only when b's least (D_hat, a') over all of A is a.
std::vector<gasp::PatchAssociation> bruteForce(const std::vector<std::vector<gasp::Feature>>& qa,
                                               const std::vector<std::vector<gasp::Feature>>& qb,
                                               const gasp::AssociationParams& p) {
  const gasp::FeatureMatch match{p.match};
  const auto best = [&](const auto& from, const auto& to, std::size_t i, double& best_hat) {
    int best_j = -1;
    best_hat = kInf;
    if (from[i].empty()) return best_j;
    for (std::size_t j = 0; j < to.size(); ++j) {
      if (to[j].empty()) continue;
      const double hat = gasp::osaDistance(from[i], to[j], match, p.costs) /
                         static_cast<double>(from[i].size() + to[j].size());
      if (hat <= p.lambda && hat < best_hat) {  // ascending j: ties keep the lowest
        best_hat = hat;
        best_j = static_cast<int>(j);
      }
    }
    return best_j;
  };
  std::vector<gasp::PatchAssociation> out;
  for (std::size_t i = 0; i < qa.size(); ++i) {
    double hat = kInf, back_hat = kInf;
    const int j = best(qa, qb, i, hat);
    if (j < 0) continue;
    if (p.mutual_check && best(qb, qa, static_cast<std::size_t>(j), back_hat) != static_cast<int>(i)) continue;
    out.push_back({static_cast<int>(i), j, hat});
  }
  return out;
}

void expectSameAssociations(const std::vector<gasp::PatchAssociation>& x, const std::vector<gasp::PatchAssociation>& y,
                            const std::string& what) {
  ASSERT_EQ(x.size(), y.size()) << what;
  for (std::size_t k = 0; k < x.size(); ++k) {
    EXPECT_EQ(x[k].a, y[k].a) << what;
    EXPECT_EQ(x[k].b, y[k].b) << what;
    EXPECT_EQ(x[k].distance, y[k].distance) << what;
  }
}

}  // namespace

TEST(ViewAssociation, RigidCopyIsAssociatedPatchForPatch) {
  const auto a = randomPatches(80, 3);
  // Includes a 180-degree roll about the optical axis.
  const gasp::Isometry3 T = Eigen::Translation3d(0.4, -0.2, 0.3) * Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitZ()) *
                            Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX());
  const auto b = moved(a, T);
  for (int k : {0, 20}) {
    gasp::AssociationParams p;
    p.feature_sets.neighbourhood.k = k;
    const auto r = gasp::associateViews(a, b, p);
    ASSERT_EQ(r.associations.size(), a.size()) << "k " << k << ": " << r.reason;
    for (const auto& s : r.associations) {
      EXPECT_EQ(s.a, s.b) << "k " << k;
      EXPECT_NEAR(s.distance, 0.0, 1e-12);
    }
    EXPECT_GT(r.stats.comparisons, 0u);
    EXPECT_LE(r.stats.comparisons, r.stats.comparisons_full);
  }
}

TEST(ViewAssociation, PartialOverlapLeavesMissingPatchesUnassociated) {
  const auto a = randomPatches(80, 5);
  auto b = a;
  b.resize(60);  // B sees only the first 60 patches
  gasp::AssociationParams p;
  p.feature_sets.neighbourhood.k = 0;
  const auto r = gasp::associateViews(a, b, p);
  int right = 0;
  for (const auto& s : r.associations) right += s.a == s.b;
  EXPECT_GE(right, 55);                                   // the shared patches are found
  EXPECT_LE(static_cast<int>(r.associations.size()), 62);  // the 20 missing ones mostly gated out
}

TEST(ViewAssociation, BadInputGivesAnEmptyResultWithAReason) {
  const auto a = randomPatches(10, 7);
  for (const auto& b : {std::vector<gasp::PatchGeometry>{}, randomPatches(1, 8)}) {
    const auto r = gasp::associateViews(a, b);
    EXPECT_TRUE(r.associations.empty());
    EXPECT_FALSE(r.reason.empty());
  }
  auto nan = a;
  for (auto& p : nan) p.centroid.x() = std::nan("");
  EXPECT_TRUE(gasp::associateViews(nan, a).associations.empty());
  gasp::AssociationParams bad;
  bad.lambda = 1.5;
  EXPECT_THROW(gasp::associateViews(a, a, bad), gasp::Error);
  bad = {};
  bad.candidates = 0;
  EXPECT_THROW(gasp::associateViews(a, a, bad), gasp::Error);
}

TEST(ViewAssociation, AllCandidatesEqualsTheBruteForceSpecification) {
  // With C >= the number of patches every patch is a candidate, whatever the key: the result
  // must be exactly the brute-force argmin (with its tie rule) and mutual check.
  const gasp::Isometry3 T = Eigen::Translation3d(0.1, 0.2, -0.1) * Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitY());
  int compared = 0;
  std::size_t associations = 0;
  for (const double sigma : {0.0, 0.01, 0.03}) {
    const auto a = sigma == 0.01 ? randomPatches(90, 11) : gridScene(13);
    const auto b = sigma == 0.0 ? moved(a, T) : noisyView(a, T, sigma, 17);
    for (const int k : {10, 25}) {
      gasp::FeatureSetParams fp = gasp::AssociationParams::defaultFeatureSets();
      fp.neighbourhood.k = k;
      const auto qa = gasp::computeFeatureSets(a, fp), qb = gasp::computeFeatureSets(b, fp);
      for (const bool mutual : {true, false}) {
        for (const double lambda : {0.5, 0.8}) {
          gasp::AssociationParams p;
          p.feature_sets = fp;
          p.candidates = 1000;
          p.mutual_check = mutual;
          p.lambda = lambda;
          const auto expected = bruteForce(qa, qb, p);
          for (const auto key : {gasp::CandidateKey::kMean, gasp::CandidateKey::kQuantiles}) {
            p.candidate_key = key;
            const auto r = gasp::associateFeatureSets(qa, qb, p);
            expectSameAssociations(r.associations, expected,
                                   "sigma " + std::to_string(sigma) + " k " + std::to_string(k) + " mutual " +
                                       std::to_string(mutual) + " lambda " + std::to_string(lambda));
            ++compared;
            associations += expected.size();
          }
        }
      }
    }
  }
  EXPECT_EQ(compared, 48);
  EXPECT_GT(associations, 1000u);
}

TEST(ViewAssociation, ResultDoesNotDependOnTheThreadCount) {
  const auto a = randomPatches(300, 21);
  const gasp::Isometry3 T = Eigen::Translation3d(0.3, 0.0, 0.2) * Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitZ());
  const auto b = noisyView(a, T, 0.02, 23);
  for (const auto key : {gasp::CandidateKey::kMean, gasp::CandidateKey::kQuantiles}) {
    gasp::AssociationParams p;
    p.candidate_key = key;
    std::vector<gasp::PatchAssociation> first;
    for (const std::size_t threads : {1, 2, 4}) {
      tbb::global_control gc(tbb::global_control::max_allowed_parallelism, threads);
      const auto r = gasp::associateViews(a, b, p);
      if (threads == 1) {
        first = r.associations;
        EXPECT_GT(first.size(), 50u);
      } else {
        expectSameAssociations(r.associations, first, "threads " + std::to_string(threads));
      }
    }
  }
}

TEST(ViewAssociation, PaperSettingsStillWork) {
  // The paper's candidate search (KD-tree over means, C = 75) and transposition costs other than
  // 0 (sparse DP instead of the bit-parallel one) on a rigid copy.
  const auto a = randomPatches(80, 31);
  const gasp::Isometry3 T = Eigen::Translation3d(-0.2, 0.1, 0.0) * Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitX());
  const auto b = moved(a, T);
  gasp::AssociationParams p;
  p.candidate_key = gasp::CandidateKey::kMean;
  p.candidates = 75;
  for (const double transpose : {0.0, 1.0}) {
    p.costs.transpose = transpose;
    const auto r = gasp::associateViews(a, b, p);
    ASSERT_EQ(r.associations.size(), a.size()) << r.reason;
    for (const auto& s : r.associations) EXPECT_EQ(s.a, s.b);
  }
}

namespace {

TEST(ViewAssociation, OneWayPartnersAreTheOnesTheMutualCheckDropped) {
  // associations + one_way (mutual check) = the associations without the mutual check, exactly.
  const gasp::Isometry3 T = Eigen::Translation3d(0.2, -0.1, 0.1) * Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX());
  for (const double sigma : {0.01, 0.03}) {
    const auto a = gridScene(21);  // grids: many patches prefer the same partner
    const auto b = noisyView(a, T, sigma, 23);
    gasp::AssociationParams p;
    p.feature_sets.neighbourhood.k = 15;
    p.lambda = 0.8;
    const auto qa = gasp::computeFeatureSets(a, p.feature_sets), qb = gasp::computeFeatureSets(b, p.feature_sets);
    const auto mutual = gasp::associateFeatureSets(qa, qb, p);
    p.mutual_check = false;
    const auto one_way = gasp::associateFeatureSets(qa, qb, p);
    EXPECT_TRUE(one_way.one_way.empty());
    auto merged = mutual.associations;
    merged.insert(merged.end(), mutual.one_way.begin(), mutual.one_way.end());
    std::sort(merged.begin(), merged.end(), [](const auto& x, const auto& y) { return x.a < y.a; });
    expectSameAssociations(merged, one_way.associations, "sigma " + std::to_string(sigma));
    EXPECT_EQ(mutual.one_way.size(), mutual.stats.not_mutual);
    EXPECT_FALSE(mutual.one_way.empty());
  }
}

}  // namespace

namespace {

TEST(ViewAssociation, DistinctivenessRatioDropsAmbiguousPartners) {
  // Grids have exact ties (interior patches with identical neighbourhoods): the ratio test must
  // drop those, keep only partners clearly better than every other candidate, and be the plain
  // search at ratio 1.
  const gasp::Isometry3 T = Eigen::Translation3d(0.1, 0.0, 0.2) * Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitZ());
  const auto a = gridScene(31);
  const auto b = noisyView(a, T, 0.01, 33);
  gasp::AssociationParams p;
  p.feature_sets.neighbourhood.k = 15;
  p.lambda = 0.8;
  p.candidates = 1000;  // every patch a candidate: the second best is exact
  p.mutual_check = false;
  const auto qa = gasp::computeFeatureSets(a, p.feature_sets), qb = gasp::computeFeatureSets(b, p.feature_sets);
  const auto plain = gasp::associateFeatureSets(qa, qb, p);
  EXPECT_EQ(plain.stats.ambiguous, 0u);
  p.distinctiveness_ratio = 0.8;
  const auto strict = gasp::associateFeatureSets(qa, qb, p);
  EXPECT_GT(strict.stats.ambiguous, 0u);
  EXPECT_LT(strict.associations.size(), plain.associations.size());
  const gasp::FeatureMatch match{p.match};
  for (const auto& s : strict.associations) {
    // Same partner as the plain search, and every other patch of B within lambda at a D_hat above
    // the partner's / 0.8.
    const auto it = std::find_if(plain.associations.begin(), plain.associations.end(),
                                 [&](const gasp::PatchAssociation& x) { return x.a == s.a; });
    ASSERT_NE(it, plain.associations.end());
    EXPECT_EQ(it->b, s.b);
    for (std::size_t j = 0; j < qb.size(); ++j) {
      if (static_cast<int>(j) == s.b || qb[j].empty()) continue;
      const double d = gasp::osaDistance(qa[static_cast<std::size_t>(s.a)], qb[j], match, p.costs) /
                       static_cast<double>(qa[static_cast<std::size_t>(s.a)].size() + qb[j].size());
      if (d <= p.lambda) {
        EXPECT_GT(0.8 * d, s.distance * (1 - 1e-12)) << "patch " << s.a << " vs " << j;
      }
    }
  }
  p.distinctiveness_ratio = 0.0;
  EXPECT_THROW(gasp::associateFeatureSets(qa, qb, p), gasp::Error);
}

}  // namespace
