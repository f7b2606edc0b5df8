// Distribution functions (gasp/core/statistics.h) against exact values: integer parameters'
// binomial sums, the closed form of F with 2 numerator degrees of freedom, the chi-square limit.
#include <gtest/gtest.h>

#include <cmath>

#include "gasp/core/error.h"
#include "gasp/core/statistics.h"

namespace {

/// I_x(a, b) for integer a, b: P(Binomial(a + b - 1, x) >= a).
double binomialTail(int a, int b, double x) {
  const int n = a + b - 1;
  double sum = 0.0;
  for (int j = a; j <= n; ++j)
    sum += std::exp(std::lgamma(n + 1.0) - std::lgamma(j + 1.0) - std::lgamma(n - j + 1.0)) * std::pow(x, j) *
           std::pow(1.0 - x, n - j);
  return sum;
}

}  // namespace

TEST(Statistics, IncompleteBetaMatchesBinomialSums) {
  EXPECT_NEAR(gasp::regularizedIncompleteBeta(6, 26, 0.3), 0.937337190664086, 1e-12);
  EXPECT_NEAR(gasp::regularizedIncompleteBeta(6, 58, 0.12), 0.7825016094427754, 1e-12);
  EXPECT_NEAR(gasp::regularizedIncompleteBeta(2, 3, 0.5), 0.6875, 1e-12);
  for (int a : {1, 3, 6, 20})
    for (int b : {1, 4, 26, 60})
      for (double x : {0.01, 0.2, 0.5, 0.77, 0.99})
        EXPECT_NEAR(gasp::regularizedIncompleteBeta(a, b, x), binomialTail(a, b, x), 1e-11) << a << " " << b << " " << x;
  EXPECT_EQ(gasp::regularizedIncompleteBeta(3, 4, 0.0), 0.0);
  EXPECT_EQ(gasp::regularizedIncompleteBeta(3, 4, 1.0), 1.0);
}

TEST(Statistics, FisherCdfAndQuantile) {
  // d1 = 2: P(F <= x) = 1 - (1 + 2 x / d2)^(-d2 / 2).
  for (double d2 : {3.0, 10.0, 52.0})
    for (double x : {0.1, 1.0, 4.0})
      EXPECT_NEAR(gasp::fisherCdf(x, 2, d2), 1.0 - std::pow(1.0 + 2.0 * x / d2, -d2 / 2.0), 1e-12);
  EXPECT_NEAR(gasp::fisherCdf(3.0, 12, 52), 0.9970263785558382, 1e-12);
  for (double p : {0.05, 0.5, 0.999})
    for (double d2 : {5.0, 52.0, 116.0})
      EXPECT_NEAR(gasp::fisherCdf(gasp::fisherQuantile(p, 12, d2), 12, d2), p, 1e-9);
  // d2 -> infinity: d1 F is chi-square of d1 degrees of freedom (its 0.999 quantile for 12: 32.909).
  EXPECT_NEAR(12.0 * gasp::fisherQuantile(0.999, 12, 1e9), 32.909, 1e-3);
}

TEST(Statistics, OutOfDomainIsNamed) {
  EXPECT_THROW(gasp::regularizedIncompleteBeta(0.0, 1.0, 0.5), gasp::Error);
  EXPECT_THROW(gasp::regularizedIncompleteBeta(1.0, 1.0, 1.5), gasp::Error);
  EXPECT_THROW(gasp::fisherCdf(-1.0, 2, 3), gasp::Error);
  // A quantile below the smallest double still ends the bisection.
  const double tiny = gasp::fisherQuantile(0.01, 0.01, 1.0);
  EXPECT_TRUE(tiny >= 0.0 && std::isfinite(tiny)) << tiny;
  EXPECT_THROW(gasp::fisherQuantile(1.0, 2, 3), gasp::Error);
  EXPECT_THROW(gasp::fisherQuantile(0.5, 0.0, 3), gasp::Error);
  EXPECT_THROW(gasp::fisherQuantile(std::nan(""), 2, 3), gasp::Error);
}
