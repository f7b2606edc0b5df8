#include "gasp/core/statistics.h"

#include <cmath>
#include <string>

#include "gasp/core/error.h"

namespace gasp {

namespace {

/// The continued fraction of I_x(a, b) (modified Lentz), converging fast for x < (a + 1) / (a + b + 2).
double betaContinuedFraction(double a, double b, double x) {
  constexpr double kTiny = 1e-300;
  constexpr int kMaxTerms = 1000;
  const auto guard = [](double v) { return std::fabs(v) < kTiny ? kTiny : v; };
  double c = 1.0, d = 1.0 / guard(1.0 - (a + b) * x / (a + 1.0));
  double f = d;
  for (int m = 1; m <= kMaxTerms; ++m) {
    const double m2 = 2.0 * m;
    // The even step, then the odd one.
    double num = m * (b - m) * x / ((a + m2 - 1.0) * (a + m2));
    d = 1.0 / guard(1.0 + num * d);
    c = guard(1.0 + num / c);
    f *= d * c;
    num = -(a + m) * (a + b + m) * x / ((a + m2) * (a + m2 + 1.0));
    d = 1.0 / guard(1.0 + num * d);
    c = guard(1.0 + num / c);
    const double delta = d * c;
    f *= delta;
    if (std::fabs(delta - 1.0) < 1e-15) break;
  }
  return f;
}

}  // namespace

double regularizedIncompleteBeta(double a, double b, double x) {
  if (!(a > 0.0) || !(b > 0.0) || !std::isfinite(a) || !std::isfinite(b) || !(x >= 0.0 && x <= 1.0))
    throw Error("regularizedIncompleteBeta: needs a, b > 0 and finite and x in [0, 1] (a " + std::to_string(a) +
                ", b " + std::to_string(b) + ", x " + std::to_string(x) + ")");
  if (x == 0.0 || x == 1.0) return x;
  // lgamma_r: std::lgamma writes the global signgam, a data race between concurrent pairs.
  int sign = 0;
  const double log_front = ::lgamma_r(a + b, &sign) - ::lgamma_r(a, &sign) - ::lgamma_r(b, &sign) + a * std::log(x) +
                           b * std::log1p(-x);
  if (x < (a + 1.0) / (a + b + 2.0)) return std::exp(log_front) * betaContinuedFraction(a, b, x) / a;
  return 1.0 - std::exp(log_front) * betaContinuedFraction(b, a, 1.0 - x) / b;
}

double fisherCdf(double x, double d1, double d2) {
  if (!(d1 > 0.0) || !(d2 > 0.0) || !(x >= 0.0))
    throw Error("fisherCdf: needs d1, d2 > 0 and x >= 0 (d1 " + std::to_string(d1) + ", d2 " + std::to_string(d2) +
                ", x " + std::to_string(x) + ")");
  if (std::isinf(x)) return 1.0;
  return regularizedIncompleteBeta(0.5 * d1, 0.5 * d2, d1 * x / (d1 * x + d2));
}

double fisherQuantile(double p, double d1, double d2) {
  if (!(p > 0.0 && p < 1.0) || !(d1 > 0.0) || !(d2 > 0.0) || !std::isfinite(d1) || !std::isfinite(d2))
    throw Error("fisherQuantile: needs p in (0, 1) and d1, d2 > 0 and finite (p " + std::to_string(p) + ", d1 " +
                std::to_string(d1) + ", d2 " + std::to_string(d2) + ")");
  double lo = 0.0, hi = 1.0;
  while (fisherCdf(hi, d1, d2) < p) {
    lo = hi, hi *= 2.0;
    if (hi > 1e300) return hi;  // p within rounding of 1
  }
  // Bisection to a relative 1e-9; at most 2100 halvings reach any double from [0, 1e300], and a
  // midpoint that no longer moves (a quantile below the smallest double) ends it too.
  for (int i = 0; i < 2100 && hi - lo > 1e-9 * hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi) break;
    (fisherCdf(mid, d1, d2) < p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace gasp
