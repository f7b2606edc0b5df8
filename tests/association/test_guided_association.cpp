// Guided association (association under a pose hypothesis): with the true pose a rigid copy is
// associated patch for patch; a wrong pose gathers almost nothing; gates, one-to-one result,
// order independence and bad input.
#include <gtest/gtest.h>

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

std::vector<gasp::PatchGeometry> scatter(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<gasp::PatchGeometry> out;
  for (int i = 0; i < n; ++i) {
    gasp::PatchGeometry p;
    p.centroid = Eigen::Vector3d(1.5 * u(rng), u(rng), 2.0 + u(rng));
    p.normal = Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized();
    out.push_back(p);
  }
  return out;
}

struct Views {
  std::vector<gasp::PatchGeometry> a, b;
  std::vector<std::vector<gasp::Feature>> qa, qb;
  gasp::AssociationParams params;
};

Views rigidCopy(const gasp::Isometry3& T_b_a, int n = 100) {
  Views v;
  v.params.feature_sets.neighbourhood.k = 15;
  v.a = scatter(n, 5);
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

TEST(GuidedAssociation, GatesAndOneToOne) {
  // Every patch of A has two partners in B near its mapped centroid: its exact copy and a copy
  // shifted by 3 cm with a normal tilted by 15 deg, both with A's feature set (D_hat 0 for both:
  // the tie goes to the nearer centroid).
  Views v = rigidCopy(gasp::Isometry3::Identity(), 60);
  const std::size_t n = v.b.size();
  for (std::size_t j = 0; j < n; ++j) {
    gasp::PatchGeometry q = v.b[j];
    q.centroid += Eigen::Vector3d(0.03, 0, 0);
    q.normal = (Eigen::AngleAxisd(15.0 * M_PI / 180.0, Eigen::Vector3d::UnitX()) * q.normal).normalized();
    v.b.push_back(q);
    v.qb.push_back(v.qb[j]);
  }
  gasp::GuidedAssociationParams gp;
  gp.lambda = 1.0;
  const auto all = gasp::guidedAssociations(v.a, v.b, v.qa, v.qb, gasp::Isometry3::Identity(), v.params, gp);
  std::vector<int> used(v.b.size(), 0);
  for (const auto& s : all) ++used[static_cast<std::size_t>(s.b)];
  EXPECT_EQ(*std::max_element(used.begin(), used.end()), 1);  // one-to-one
  EXPECT_EQ(all.size(), v.a.size());
  // The distance gate below 3 cm, or the angle gate below 15 deg: only exact copies remain.
  for (const int which : {0, 1}) {
    gasp::GuidedAssociationParams tight = gp;
    if (which == 0) tight.max_distance_m = 0.02;
    else tight.max_normal_angle_deg = 10.0;
    const auto g = gasp::guidedAssociations(v.a, v.b, v.qa, v.qb, gasp::Isometry3::Identity(), v.params, tight);
    EXPECT_EQ(g.size(), v.a.size());
    for (const auto& s : g) EXPECT_LT(static_cast<std::size_t>(s.b), n) << "gate " << which;
  }
  // lambda 0: only identical feature sets.
  gp.lambda = 0.0;
  for (const auto& s : gasp::guidedAssociations(v.a, v.b, v.qa, v.qb, gasp::Isometry3::Identity(), v.params, gp))
    EXPECT_EQ(s.distance, 0.0);
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
