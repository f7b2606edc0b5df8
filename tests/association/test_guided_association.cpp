// Guided association (association under a pose hypothesis): with the true pose a rigid copy is
// associated patch for patch; a wrong pose gathers almost nothing; distance, normal and lambda
// gates; one-to-one result independent of B's order and of the thread count; bad input.
#include <gtest/gtest.h>

#include <tbb/global_control.h>

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

TEST(GuidedAssociation, TheResultDoesNotDependOnTheThreadCount) {
  // A pose 2 cm / 1 deg off and lambda 1: most patches of A have several candidates within the
  // gate, so the per-patch choices are not trivial; the patches of A are searched in parallel.
  const Views v = rigidCopy(kRoll, 400);
  const gasp::Isometry3 off =
      Eigen::Translation3d(0.02, 0, 0) * kRoll * Eigen::AngleAxisd(M_PI / 180.0, Eigen::Vector3d::UnitX());
  gasp::GuidedAssociationParams gp;
  gp.lambda = 1.0;
  gp.max_distance_m = 0.3;
  std::vector<gasp::PatchAssociation> first;
  for (const std::size_t threads : {1, 2, 4}) {
    tbb::global_control gc(tbb::global_control::max_allowed_parallelism, threads);
    const auto g = gasp::guidedAssociations(v.a, v.b, v.qa, v.qb, off, v.params, gp);
    if (threads == 1) {
      first = g;
      EXPECT_GT(first.size(), 200u);
      continue;
    }
    ASSERT_EQ(g.size(), first.size()) << threads << " threads";
    for (std::size_t k = 0; k < g.size(); ++k) {
      EXPECT_EQ(g[k].a, first[k].a);
      EXPECT_EQ(g[k].b, first[k].b);
      EXPECT_EQ(g[k].distance, first[k].distance);
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
