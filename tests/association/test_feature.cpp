// The invariant feature q(mu, alpha) (NOTES item 2) on hand-made configurations, and bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "gasp/association/invariant_feature.h"
#include "gasp/core/error.h"

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;

gasp::PatchGeometry patch(Eigen::Vector3d c, Eigen::Vector3d n) { return gasp::PatchGeometry{c, n}; }

void expectFeature(const gasp::Feature& q, const gasp::Feature& expected) {
  for (std::size_t i = 0; i < 7; ++i) EXPECT_NEAR(q[i], expected[i], 1e-12) << "component " << i;
}

const gasp::PatchGeometry kMu = patch({0, 0, 0}, {0, 0, 1});

}  // namespace

TEST(InvariantFeature, NeighbourStraightAheadIsDegenerate) {
  // r parallel to n_mu: v undefined, all signs 0; theta(r, n_mu) = 0.
  auto q = gasp::computeFeature(kMu, patch({0, 0, 1.5}, {0, 0, 1}));
  ASSERT_TRUE(q);
  expectFeature(*q, {0, 0, 0, 1.5, 0, 0, 0});
  // Straight behind, neighbour normal tilted by 90 deg.
  q = gasp::computeFeature(kMu, patch({0, 0, -2}, {1, 0, 0}));
  ASSERT_TRUE(q);
  expectFeature(*q, {0, 0, 0, 2, kPi / 2, kPi, kPi / 2});
  // Within e_theta (3 deg) of n_mu: still degenerate.
  q = gasp::computeFeature(kMu, patch({std::sin(3 * kDeg), 0, std::cos(3 * kDeg)}, {1, 0, 0}));
  ASSERT_TRUE(q);
  EXPECT_EQ((*q)[0], 0.0);
  EXPECT_EQ((*q)[1], 0.0);
  EXPECT_EQ((*q)[2], 0.0);
  EXPECT_NEAR((*q)[5], 3 * kDeg, 1e-12);
}

TEST(InvariantFeature, PerpendicularNeighbourWithKnownSigns) {
  // r = (2,0,0): u = x, v = z (n_mu projected), w = u x v = -y.
  auto q = gasp::computeFeature(kMu, patch({2, 0, 0}, {0, 0, 1}));  // parallel normals
  ASSERT_TRUE(q);
  expectFeature(*q, {0, 2, 0, 2, 0, kPi / 2, kPi / 2});
  q = gasp::computeFeature(kMu, patch({2, 0, 0}, {1, 0, 0}));  // n_alpha along r
  ASSERT_TRUE(q);
  expectFeature(*q, {2, 0, 0, 2, kPi / 2, kPi / 2, 0});
  q = gasp::computeFeature(kMu, patch({2, 0, 0}, {-1, 0, 0}));  // n_alpha against r
  ASSERT_TRUE(q);
  expectFeature(*q, {-2, 0, 0, 2, kPi / 2, kPi / 2, kPi});
  q = gasp::computeFeature(kMu, patch({2, 0, 0}, {0, -1, 0}));  // n_alpha along w
  ASSERT_TRUE(q);
  expectFeature(*q, {0, 0, 2, 2, kPi / 2, kPi / 2, kPi / 2});
  q = gasp::computeFeature(kMu, patch({2, 0, 0}, {0, 1, 0}));  // against w
  ASSERT_TRUE(q);
  expectFeature(*q, {0, 0, -2, 2, kPi / 2, kPi / 2, kPi / 2});
}

TEST(InvariantFeature, GeneralConfiguration) {
  // n_alpha = (1, -1, 1)/sqrt(3): positive along u, v and w.
  const Eigen::Vector3d na = Eigen::Vector3d(1, -1, 1).normalized();
  const auto q = gasp::computeFeature(kMu, patch({0.5, 0, 0}, na * 7.0));  // normal rescaled
  ASSERT_TRUE(q);
  const double a = std::acos(1.0 / std::sqrt(3.0));
  expectFeature(*q, {0.5, 0.5, 0.5, 0.5, a, kPi / 2, a});
  // Translating both patches does not change q.
  const Eigen::Vector3d t(3, -4, 5);
  const auto q2 = gasp::computeFeature(patch(kMu.centroid + t, kMu.normal), patch(Eigen::Vector3d(0.5, 0, 0) + t, na));
  ASSERT_TRUE(q2);
  expectFeature(*q2, *q);
}

TEST(InvariantFeature, SignToleranceAroundNinetyDegrees) {
  // n_alpha tilted from v (= z) towards u (= x) by 3 deg: n_a.u = sin 3 deg < sin 5 deg -> 0.
  const auto tilt = [](double deg) { return Eigen::Vector3d(std::sin(deg * kDeg), 0, std::cos(deg * kDeg)); };
  auto q = gasp::computeFeature(kMu, patch({2, 0, 0}, tilt(3)));
  ASSERT_TRUE(q);
  EXPECT_EQ((*q)[0], 0.0);
  EXPECT_EQ((*q)[1], 2.0);
  q = gasp::computeFeature(kMu, patch({2, 0, 0}, tilt(7)));
  ASSERT_TRUE(q);
  EXPECT_EQ((*q)[0], 2.0);
  q = gasp::computeFeature(kMu, patch({2, 0, 0}, tilt(-7)));
  ASSERT_TRUE(q);
  EXPECT_EQ((*q)[0], -2.0);
  // e_theta = 10 deg: 7 deg is now within tolerance.
  gasp::FeatureParams wide;
  wide.e_theta_rad = 10 * kDeg;
  q = gasp::computeFeature(kMu, patch({2, 0, 0}, tilt(7)), wide);
  ASSERT_TRUE(q);
  EXPECT_EQ((*q)[0], 0.0);
  EXPECT_EQ(gasp::toleranceSign(0.05, std::sin(5 * kDeg)), 0.0);
  EXPECT_EQ(gasp::toleranceSign(-0.1, std::sin(5 * kDeg)), -1.0);
}

TEST(InvariantFeature, BadInputGivesNoFeature) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(gasp::computeFeature(kMu, patch({nan, 0, 0}, {0, 0, 1})));
  EXPECT_FALSE(gasp::computeFeature(kMu, patch({1, 0, 0}, {0, nan, 1})));
  EXPECT_FALSE(gasp::computeFeature(kMu, patch({inf, 0, 0}, {0, 0, 1})));
  EXPECT_FALSE(gasp::computeFeature(kMu, patch({1, 0, 0}, {0, 0, 0})));  // zero normal
  EXPECT_FALSE(gasp::computeFeature(patch({0, 0, 0}, {nan, 0, 0}), patch({1, 0, 0}, {0, 0, 1})));
  EXPECT_FALSE(gasp::computeFeature(kMu, patch({0, 0, 0}, {0, 1, 0})));      // coincident centroids
  EXPECT_FALSE(gasp::computeFeature(kMu, patch({1e-8, 0, 0}, {0, 1, 0})));   // closer than 1e-6 m
  EXPECT_TRUE(gasp::computeFeature(kMu, patch({1e-5, 0, 0}, {0, 1, 0})));
}

TEST(InvariantFeature, InvalidParamsThrow) {
  gasp::FeatureParams p;
  EXPECT_NO_THROW(gasp::validate(p));
  p.e_theta_rad = -0.1;
  EXPECT_THROW(gasp::validate(p), gasp::Error);
  p.e_theta_rad = kPi / 2;
  EXPECT_THROW(gasp::validate(p), gasp::Error);
  p = gasp::FeatureParams{};
  p.min_separation_m = std::nan("");
  EXPECT_THROW(gasp::validate(p), gasp::Error);
}
