#pragma once
/// \file statistics.h Distribution functions the pipeline's tests of significance need.

namespace gasp {

/// The regularised incomplete beta function I_x(a, b) for a, b > 0 and x in [0, 1] (a continued
/// fraction, relative accuracy about 1e-12). Throws gasp::Error outside that domain.
double regularizedIncompleteBeta(double a, double b, double x);

/// P(F <= x) for Fisher's F distribution of d1 and d2 degrees of freedom (x >= 0).
double fisherCdf(double x, double d1, double d2);

/// The p-quantile of Fisher's F distribution of d1 and d2 degrees of freedom, p in (0, 1) (by
/// bisection on fisherCdf, to 1e-9 relative). Throws gasp::Error outside those domains.
double fisherQuantile(double p, double d1, double d2);

}  // namespace gasp
