#pragma once
/// \file feature_match.h Match(q, q') of the matching stage (paper section III-D, Algorithm 1,
/// corrected in NOTES item 4): every component within its deviation threshold.
#include <cmath>

#include "gasp/association/invariant_feature.h"

namespace gasp {

/// Deviation thresholds of Match (paper experiments: r_dev = 0.04 m, theta_dev = 10 deg).
/// ERRATUM (NOTES item 4): the paper's listing applies theta_dev to the first three components
/// and r_dev to the last four; the first FOUR components are distances (r_dev) and the LAST THREE
/// are angles (theta_dev).
struct MatchParams {
  double r_dev_m = 0.04;                                       ///< components 0..3 [m]
  double theta_dev_rad = 10.0 * 3.14159265358979323846 / 180.0;  ///< components 4..6 [rad]
};

/// Throws gasp::Error unless both thresholds are finite and >= 0.
void validate(const MatchParams& params);

/// Match(q, q'): |q_i - q'_i| <= r_dev for i < 4 and <= theta_dev for i >= 4. Symmetric, not
/// transitive. NaN components never match.
struct FeatureMatch {
  MatchParams params;
  bool operator()(const Feature& a, const Feature& b) const {
    // Branch-free (bitwise &): in the DP inner loop, which components fail is unpredictable and
    // mispredicted branches cost more than evaluating all seven.
    const double r = params.r_dev_m, t = params.theta_dev_rad;
    return (std::abs(a[0] - b[0]) <= r) & (std::abs(a[1] - b[1]) <= r) &
           (std::abs(a[2] - b[2]) <= r) & (std::abs(a[3] - b[3]) <= r) &
           (std::abs(a[4] - b[4]) <= t) & (std::abs(a[5] - b[5]) <= t) &
           (std::abs(a[6] - b[6]) <= t);
  }
};

}  // namespace gasp
