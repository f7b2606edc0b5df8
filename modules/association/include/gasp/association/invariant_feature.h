#pragma once
/// \file invariant_feature.h The 7-component rigid-motion invariant feature q(mu, alpha) of a
/// patch mu and one neighbour alpha (paper section III-B, corrected in NOTES item 2).
#include <array>
#include <cstddef>
#include <optional>

#include "gasp/association/patch_geometry.h"

namespace gasp {

/// q(mu, alpha). Components 0..3 are distances [m], 4..6 angles [rad]:
///   q = [ |r| sgn_e(n_a.u), |r| sgn_e(n_a.v), |r| sgn_e(n_a.w), |r|,
///         theta(n_mu, n_a), theta(r, n_mu), theta(r, n_a) ]
/// with r = l_a - l_mu, u = r/|r|, v = normalised(n_mu - (n_mu.u) u), w = u x v.
using Feature = std::array<double, 7>;

/// Number of distance-like components (they come first), and of angle components (last).
inline constexpr std::size_t kFeatureDistanceComponents = 4;
inline constexpr std::size_t kFeatureAngleComponents = 3;

/// Parameters of the feature.
struct FeatureParams {
  /// e_theta [rad], paper: 5 deg. sgn_e(x) = 0 when the angle between n_alpha and the basis vector
  /// is within e_theta of 90 deg (|x| < sin(e_theta)); all three signs are 0 when the basis is
  /// degenerate (theta(r, n_mu) within e_theta of 0 or pi). Must be in [0, pi/2).
  double e_theta_rad = 5.0 * 3.14159265358979323846 / 180.0;
  /// Neighbours closer than this to mu [m] have no direction r/|r|: they give no feature.
  double min_separation_m = 1e-6;
};

/// Throws gasp::Error when a parameter is out of range.
void validate(const FeatureParams& params);

/// sgn_e(x): 0 when |x| < sin(e_theta), else +1 or -1 (paper eq. for q, NOTES item 2).
double toleranceSign(double x, double sin_e_theta);

/// q(mu, alpha) (NOTES item 2). Normals are normalised here. Returns no feature when the input
/// is non-finite, a normal has zero length, or the centroids coincide (|r| < min_separation_m):
/// the caller skips that neighbour. Does not validate params (see validate()).
std::optional<Feature> computeFeature(const PatchGeometry& mu, const PatchGeometry& alpha,
                                      const FeatureParams& params = {});

}  // namespace gasp
