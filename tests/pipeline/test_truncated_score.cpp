// The line search's objective (truncated_score.h): sum of w (g^2 - r^2)_+ over the terms, r the
// point-to-plane residual.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "gasp/pipeline/truncated_score.h"

using namespace gasp;

namespace {

/// `n` pixel terms (weight 1) on the plane z = 1 (normal +z) and `m` edge terms (weight 2) on the
/// plane x = 0 (normal +x), each source point on its plane at the identity.
GatedTerms planes(int n, int m, double pixel_gate, double edge_gate) {
  GatedTerms t;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d p(0.01 * i, -0.02 * i, 1.0);
    t.terms.push_back({p, p, Eigen::Vector3d::UnitZ(), 1.0});
  }
  t.pixel_terms = t.terms.size();
  for (int i = 0; i < m; ++i) {
    const Eigen::Vector3d p(0.0, 0.03 * i, 2.0);
    t.terms.push_back({p, p, Eigen::Vector3d::UnitX(), 2.0});
  }
  t.pixel_gate_m = pixel_gate;
  t.edge_gate_m = edge_gate;
  return t;
}

Isometry3 shifted(const Eigen::Vector3d& d) {
  Isometry3 T = Isometry3::Identity();
  T.translation() = d;
  return T;
}

}  // namespace

TEST(TruncatedScore, IsTheSumOfTruncatedQuadratics) {
  const GatedTerms t = planes(10, 4, 0.03, 0.09);
  // At the identity every residual is 0: each term scores its weight times its gate squared.
  EXPECT_NEAR(truncatedScore(t, Isometry3::Identity()), 10 * 0.03 * 0.03 + 4 * 2.0 * 0.09 * 0.09, 1e-12);
  // 1 cm along z: the pixel terms' residuals are 1 cm, the edge terms' (normal x) still 0.
  EXPECT_NEAR(truncatedScore(t, shifted({0, 0, 0.01})), 10 * (0.03 * 0.03 - 0.01 * 0.01) + 4 * 2.0 * 0.09 * 0.09, 1e-12);
  // Sliding along both planes (y) changes nothing: point-to-plane residuals.
  EXPECT_NEAR(truncatedScore(t, shifted({0, 0.05, 0})), truncatedScore(t, Isometry3::Identity()), 1e-12);
  // 5 cm along z: beyond the pixel gate those terms score 0, not less; the edge terms' gate is wider.
  EXPECT_NEAR(truncatedScore(t, shifted({0.05, 0, 0.05})), 4 * 2.0 * (0.09 * 0.09 - 0.05 * 0.05), 1e-12);
}

TEST(TruncatedScore, FallsAsTheResidualsGrow) {
  const GatedTerms t = planes(20, 5, 0.03, 0.06);
  double before = truncatedScore(t, Isometry3::Identity());
  for (double d = 0.005; d < 0.1; d += 0.005) {
    const double now = truncatedScore(t, shifted({d, 0, d}));
    EXPECT_LT(now, before) << d;
    EXPECT_GE(now, 0.0) << d;
    before = now;
    if (now == 0.0) break;
  }
  EXPECT_EQ(before, 0.0);
}

TEST(TruncatedScore, EmptyAndNonFiniteTermsScoreNothing) {
  EXPECT_EQ(truncatedScore(GatedTerms{}, Isometry3::Identity()), 0.0);
  GatedTerms t = planes(4, 0, 0.03, 0.03);
  t.terms[1].p_source.z() = std::numeric_limits<double>::quiet_NaN();
  t.terms[2].q_target.z() = std::numeric_limits<double>::infinity();
  t.terms[3].weight = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NEAR(truncatedScore(t, Isometry3::Identity()), 0.03 * 0.03, 1e-12);
  EXPECT_TRUE(std::isfinite(truncatedScore(t, shifted({0, 0, 0.01}))));
}
