// Guided association (association under a pose hypothesis): with the true pose a rigid copy is
// associated patch for patch; a wrong pose gathers almost nothing; distance, normal and lambda
// gates; one-to-one result independent of B's order and of the thread count; bad input.
#include <gtest/gtest.h>

#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "gasp/association/feature_sets.h"
#include "gasp/association/guided_association.h"
#include "gasp/core/error.h"
#include "patch_motion.h"

namespace {

using gasp::test::moved;
using gasp::test::randomPatches;

struct Views {
  std::vector<gasp::PatchGeometry> a, b;
  std::vector<std::vector<gasp::Feature>> qa, qb;
  gasp::AssociationParams params;
};

Views rigidCopy(const gasp::Isometry3& T_b_a, int n = 100) {
  Views v;
  v.params.feature_sets.neighbourhood.k = 15;
  v.a = randomPatches(n, 5);
  v.b = moved(v.a, T_b_a);
  std::reverse(v.b.begin(), v.b.end());  // patch i of A is patch n-1-i of B
  v.qa = gasp::computeFeatureSets(v.a, v.params.feature_sets);
  v.qb = gasp::computeFeatureSets(v.b, v.params.feature_sets);
  return v;
}

const gasp::Isometry3 kRoll =
    Eigen::Translation3d(0.3, -0.2, 0.4) * Eigen::AngleAxisd(M_PI, Eigen::Vector3d(0.1, 0.2, 1.0).normalized());

TEST(GuidedAssociation, TruePoseAssociatesARigidCopyPatchForPatch) {
  const Views v = rigidCopy(kRoll);
  const auto g = gasp::guidedAssociations(v.a, v.b, v.qa, v.qb, kRoll, v.params);
  ASSERT_EQ(g.size(), v.a.size());
  for (std::size_t k = 0; k < g.size(); ++k) {
    EXPECT_EQ(g[k].a, static_cast<int>(k));
    EXPECT_EQ(g[k].b, static_cast<int>(v.a.size() - 1 - k));
    EXPECT_EQ(g[k].distance, 0.0);
  }
}

TEST(GuidedAssociation, AWrongPoseGathersAlmostNothing) {
  const Views v = rigidCopy(kRoll);
  for (const gasp::Isometry3& wrong :
       {gasp::Isometry3(Eigen::Translation3d(0.25, 0, 0) * kRoll), gasp::Isometry3(kRoll * Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitY())),
        gasp::Isometry3::Identity()}) {
    const auto g = gasp::guidedAssociations(v.a, v.b, v.qa, v.qb, wrong, v.params);
    EXPECT_LE(g.size(), 3u);
  }
}

TEST(GuidedAssociation, DistanceAndNormalGates) {
  // B holds only copies of A's patches shifted by 3 cm and with normals tilted by 15 deg, each
  // with its original's feature set (D_hat 0): the gates alone decide.
  Views v = rigidCopy(gasp::Isometry3::Identity(), 60);
  std::vector<gasp::PatchGeometry> shifted;
  std::vector<std::vector<gasp::Feature>> q_shifted;
  for (std::size_t i = 0; i < v.a.size(); ++i) {
    gasp::PatchGeometry q = v.a[i];
    q.centroid += Eigen::Vector3d(0.03, 0, 0);
    const Eigen::Vector3d axis = q.normal.unitOrthogonal();  // tilt by exactly 15 deg
    q.normal = (Eigen::AngleAxisd(15.0 * M_PI / 180.0, axis) * q.normal).normalized();
    shifted.push_back(q);
    q_shifted.push_back(v.qa[i]);
  }
  const gasp::Isometry3 I = gasp::Isometry3::Identity();
  gasp::GuidedAssociationParams gp;  // 3.5 cm, 20 deg: every shifted copy passes
  const auto all = gasp::guidedAssociations(v.a, shifted, v.qa, q_shifted, I, v.params, gp);
  ASSERT_EQ(all.size(), v.a.size());
  for (const auto& s : all) {
    EXPECT_EQ(s.a, s.b);
    EXPECT_EQ(s.distance, 0.0);
  }
  gasp::GuidedAssociationParams tight = gp;
  tight.max_distance_m = 0.02;
  EXPECT_TRUE(gasp::guidedAssociations(v.a, shifted, v.qa, q_shifted, I, v.params, tight).empty());
  tight = gp;
  tight.max_normal_angle_deg = 10.0;
  EXPECT_TRUE(gasp::guidedAssociations(v.a, shifted, v.qa, q_shifted, I, v.params, tight).empty());
}

TEST(GuidedAssociation, LambdaGatesTheFeatureSets) {
  // B = A unmoved, but each patch of B carries the feature set of another patch: only gated by
  // lambda. lambda 0 keeps nothing; lambda 1 keeps every patch (D_hat <= 1 always).
  Views v = rigidCopy(gasp::Isometry3::Identity(), 40);
  auto b = v.b;
  std::reverse(b.begin(), b.end());  // b[i] = a[i] again
  auto qb = v.qa;
  std::rotate(qb.begin(), qb.begin() + 1, qb.end());
  gasp::GuidedAssociationParams gp;
  gp.lambda = 0.0;
  EXPECT_TRUE(gasp::guidedAssociations(v.a, b, v.qa, qb, gasp::Isometry3::Identity(), v.params, gp).empty());
  gp.lambda = 1.0;
  const auto g = gasp::guidedAssociations(v.a, b, v.qa, qb, gasp::Isometry3::Identity(), v.params, gp);
  EXPECT_EQ(g.size(), v.a.size());
  for (const auto& s : g) EXPECT_GT(s.distance, 0.0);
}

TEST(GuidedAssociation, OneToOneKeepsTheBestChooser) {
  // Patch 0 of A has a twin 1 cm away with a worse feature set (patch 5's); both map onto patch
  // 0 of B. B's patch keeps the better chooser (D_hat 0); the twin gets nothing.
  Views v = rigidCopy(gasp::Isometry3::Identity(), 40);
  auto b = v.b;
  std::reverse(b.begin(), b.end());
  const auto qb = v.qa;
  auto a = v.a;
  auto qa = v.qa;
  gasp::PatchGeometry twin = a[0];
  twin.centroid += Eigen::Vector3d(0.01, 0, 0);
  a.push_back(twin);
  qa.push_back(v.qa[5]);
  gasp::GuidedAssociationParams gp;
  gp.lambda = 1.0;
  const auto g = gasp::guidedAssociations(a, b, qa, qb, gasp::Isometry3::Identity(), v.params, gp);
  std::vector<int> chosen(b.size(), 0);
  for (const auto& s : g) ++chosen[static_cast<std::size_t>(s.b)];
  EXPECT_EQ(*std::max_element(chosen.begin(), chosen.end()), 1);
  bool zero_has_zero = false;
  for (const auto& s : g) {
    EXPECT_NE(s.a, 40) << "the twin must lose patch 0 of B";
    zero_has_zero |= s.a == 0 && s.b == 0 && s.distance == 0.0;
  }
  EXPECT_TRUE(zero_has_zero);
  // The same associations whatever the order of B's patches (ties are broken by index only
  // after D_hat and distance).
  auto b_rev = b;
  auto qb_rev = qb;
  std::reverse(b_rev.begin(), b_rev.end());
  std::reverse(qb_rev.begin(), qb_rev.end());
  const auto g_rev = gasp::guidedAssociations(a, b_rev, qa, qb_rev, gasp::Isometry3::Identity(), v.params, gp);
  ASSERT_EQ(g_rev.size(), g.size());
  for (std::size_t k = 0; k < g.size(); ++k) {
    EXPECT_EQ(g_rev[k].a, g[k].a);
    EXPECT_EQ(g_rev[k].b, static_cast<int>(b.size()) - 1 - g[k].b);
  }
}

// The rule of guided_association.h written out plainly: every patch of B against every patch of
// A, the full edit distance, the least (D_hat, squared distance, a, b), then one patch of A per
// patch of B (its best chooser).
std::vector<gasp::PatchAssociation> naiveGuided(const Views& v, const std::vector<gasp::PatchGeometry>& b,
                                                const std::vector<std::vector<gasp::Feature>>& qb,
                                                const gasp::Isometry3& T_b_a, const gasp::GuidedAssociationParams& gp) {
  struct Best {
    int a = -1, b = -1;
    double hat = std::numeric_limits<double>::infinity(), sq = 0.0;
    bool betterThan(const Best& o) const {
      if (o.b < 0) return true;
      if (hat != o.hat) return hat < o.hat;
      if (sq != o.sq) return sq < o.sq;
      return a != o.a ? a < o.a : b < o.b;
    }
  };
  const double min_cos = std::cos(gp.max_normal_angle_deg * M_PI / 180.0);
  gasp::EditDistanceWorkspace ws;
  std::vector<Best> per_a;
  for (std::size_t i = 0; i < v.a.size(); ++i) {
    Best best;
    const Eigen::Vector3d c = T_b_a * v.a[i].centroid;
    const Eigen::Vector3d n = (T_b_a.linear() * v.a[i].normal).normalized();
    for (std::size_t j = 0; j < b.size(); ++j) {
      const double sq = (c - b[j].centroid).squaredNorm();
      if (sq > gp.max_distance_m * gp.max_distance_m || n.dot(b[j].normal.normalized()) < min_cos) continue;
      const double d = gasp::featureSetDistance(v.qa[i], qb[j], v.params.match, v.params.costs,
                                                std::numeric_limits<double>::infinity(), ws);
      const Best cand{static_cast<int>(i), static_cast<int>(j), d / static_cast<double>(v.qa[i].size() + qb[j].size()), sq};
      if (cand.hat <= gp.lambda && cand.betterThan(best)) best = cand;
    }
    if (best.b >= 0) per_a.push_back(best);
  }
  std::vector<int> owner(b.size(), -1);
  for (std::size_t k = 0; k < per_a.size(); ++k) {
    int& o = owner[static_cast<std::size_t>(per_a[k].b)];
    if (o < 0 || per_a[k].betterThan(per_a[static_cast<std::size_t>(o)])) o = static_cast<int>(k);
  }
  std::vector<gasp::PatchAssociation> out;
  for (std::size_t k = 0; k < per_a.size(); ++k)
    if (owner[static_cast<std::size_t>(per_a[k].b)] == static_cast<int>(k)) out.push_back({per_a[k].a, per_a[k].b, per_a[k].hat});
  return out;
}

TEST(GuidedAssociation, EqualsThePlainRuleForAnyThreadCount) {
  // 1500 patches, B a noisy copy (1 cm centroids, a few degrees on the normals), a pose 2 cm /
  // 1 deg off, a 0.3 m gate, no normal gate and lambda 1: most patches of A have several
  // candidates with D_hat > 0, so every choice and tie rule counts. The patches of A are searched
  // in parallel; the result must be the plain rule's, whatever the thread count.
  Views v = rigidCopy(kRoll, 1500);
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, 0.01);
  for (auto& p : v.b) {
    p.centroid += Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
    p.normal = (p.normal + 5.0 * Eigen::Vector3d(noise(rng), noise(rng), noise(rng))).normalized();
  }
  v.qb = gasp::computeFeatureSets(v.b, v.params.feature_sets);
  const gasp::Isometry3 off =
      Eigen::Translation3d(0.02, 0, 0) * kRoll * Eigen::AngleAxisd(M_PI / 180.0, Eigen::Vector3d::UnitX());
  gasp::GuidedAssociationParams gp;
  gp.lambda = 1.0;
  gp.max_distance_m = 0.3;
  gp.max_normal_angle_deg = 180.0;

  int several = 0;
  for (const auto& pa : v.a) {
    int within = 0;
    for (const auto& pb : v.b) within += ((off * pa.centroid) - pb.centroid).norm() <= gp.max_distance_m;
    several += within >= 2;
  }
  EXPECT_GT(several, 1000) << "the test needs patches with several candidates";

  const auto expected = naiveGuided(v, v.b, v.qb, off, gp);
  ASSERT_GT(expected.size(), 1000u);
  int not_exact = 0;
  for (const auto& e : expected) not_exact += e.distance > 0.0;
  EXPECT_GT(not_exact, 1000);

  tbb::global_control gc(tbb::global_control::max_allowed_parallelism, 4);
  for (const int threads : {1, 2, 4}) {
    tbb::task_arena arena(threads);
    std::vector<gasp::PatchAssociation> g;
    arena.execute([&] { g = gasp::guidedAssociations(v.a, v.b, v.qa, v.qb, off, v.params, gp); });
    ASSERT_EQ(g.size(), expected.size()) << threads << " threads";
    for (std::size_t k = 0; k < g.size(); ++k) {
      EXPECT_EQ(g[k].a, expected[k].a) << threads << " threads, association " << k;
      EXPECT_EQ(g[k].b, expected[k].b) << threads << " threads, association " << k;
      EXPECT_EQ(g[k].distance, expected[k].distance) << threads << " threads, association " << k;
    }
  }
}

TEST(GuidedAssociation, BadInput) {
  const Views v = rigidCopy(kRoll, 30);
  gasp::GuidedAssociationParams gp;
  gp.max_distance_m = 0.0;
  EXPECT_THROW(gasp::guidedAssociations(v.a, v.b, v.qa, v.qb, kRoll, v.params, gp), gasp::Error);
  gp = {};
  gp.lambda = 1.5;
  EXPECT_THROW(gasp::guidedAssociations(v.a, v.b, v.qa, v.qb, kRoll, v.params, gp), gasp::Error);
  auto short_q = v.qb;
  short_q.pop_back();
  EXPECT_THROW(gasp::guidedAssociations(v.a, v.b, v.qa, short_q, kRoll, v.params), gasp::Error);
  gasp::Isometry3 nan_pose = kRoll;
  nan_pose.translation().x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(gasp::guidedAssociations(v.a, v.b, v.qa, v.qb, nan_pose, v.params).empty());
  auto a_nan = v.a;
  a_nan[3].centroid.x() = std::numeric_limits<double>::quiet_NaN();
  const auto g = gasp::guidedAssociations(a_nan, v.b, v.qa, v.qb, kRoll, v.params);
  for (const auto& s : g) EXPECT_NE(s.a, 3);
  EXPECT_TRUE(gasp::guidedAssociations({}, {}, {}, {}, kRoll, v.params).empty());
}

}  // namespace
