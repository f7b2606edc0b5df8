#include "gasp/association/invariant_feature.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <string>

#include "gasp/core/error.h"

namespace gasp {
namespace {

constexpr double kHalfPi = 1.57079632679489661923;

/// theta(a, b) for unit vectors: acos of the clamped dot product [rad].
double angleBetweenUnit(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::acos(std::clamp(a.dot(b), -1.0, 1.0));
}

/// Unit vector of n, or nothing when n is not finite or has (almost) zero length.
std::optional<Eigen::Vector3d> unitOrNothing(const Eigen::Vector3d& n) {
  if (!n.allFinite()) return std::nullopt;
  const double len = n.norm();
  if (!(len > 1e-12)) return std::nullopt;
  return Eigen::Vector3d(n / len);
}

}  // namespace

void validate(const FeatureParams& params) {
  if (!(params.e_theta_rad >= 0.0 && params.e_theta_rad < kHalfPi)) {
    throw Error("FeatureParams::e_theta_rad must be in [0, pi/2) rad, got " +
                std::to_string(params.e_theta_rad));
  }
  if (!(params.min_separation_m >= 0.0) || !std::isfinite(params.min_separation_m)) {
    throw Error("FeatureParams::min_separation_m must be finite and >= 0 m, got " +
                std::to_string(params.min_separation_m));
  }
}

double toleranceSign(double x, double sin_e_theta) {
  if (std::abs(x) < sin_e_theta) return 0.0;
  return x > 0.0 ? 1.0 : -1.0;
}

std::optional<Feature> computeFeature(const PatchGeometry& mu, const PatchGeometry& alpha,
                                      const FeatureParams& params) {
  if (!mu.centroid.allFinite() || !alpha.centroid.allFinite()) return std::nullopt;
  const auto n_mu = unitOrNothing(mu.normal);
  const auto n_a = unitOrNothing(alpha.normal);
  if (!n_mu || !n_a) return std::nullopt;

  const Eigen::Vector3d r = alpha.centroid - mu.centroid;
  const double dist = r.norm();
  if (!std::isfinite(dist) || dist < params.min_separation_m || dist == 0.0) return std::nullopt;
  const Eigen::Vector3d u = r / dist;

  const double theta_r_mu = angleBetweenUnit(u, *n_mu);
  const double sin_e = std::sin(params.e_theta_rad);

  Feature q{};
  // Degenerate basis: r (almost) parallel to n_mu, so v = n_mu - (n_mu.u) u is not defined
  // (NOTES item 2): all three signs are 0.
  const bool degenerate =
      theta_r_mu < params.e_theta_rad || theta_r_mu > (2.0 * kHalfPi - params.e_theta_rad);
  if (!degenerate) {
    Eigen::Vector3d v = *n_mu - n_mu->dot(u) * u;
    const double v_len = v.norm();
    if (v_len > 1e-12) {  // always true when not degenerate and e_theta > 0
      v /= v_len;
      const Eigen::Vector3d w = u.cross(v);
      q[0] = dist * toleranceSign(n_a->dot(u), sin_e);
      q[1] = dist * toleranceSign(n_a->dot(v), sin_e);
      q[2] = dist * toleranceSign(n_a->dot(w), sin_e);
    }
  }
  q[3] = dist;
  q[4] = angleBetweenUnit(*n_mu, *n_a);
  q[5] = theta_r_mu;
  q[6] = angleBetweenUnit(u, *n_a);
  // Avoid -0.0 so that equal features are bitwise equal.
  for (double& x : q) x += 0.0;
  return q;
}

}  // namespace gasp
