// The association of two views (paper III-E): exact on noise-free rigid copies, empty with a
// reason on bad input.
#include <gtest/gtest.h>

#include <random>

#include "gasp/association/view_association.h"
#include "gasp/core/error.h"
#include "patch_motion.h"
#include "gasp/core/pose.h"

namespace {

using gasp::test::moved;

/// n patches scattered in a 3 x 2 x 2 m box with random unit normals (fixed seed).
std::vector<gasp::PatchGeometry> randomPatches(int n, unsigned seed) {
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
