#pragma once
// Surface area seen by one pixel: its frontal area (ViewProjection::frontalArea: z^2 / (fx fy) for
// a pinhole) / cos(incidence), the incidence clamped.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>

#include "gasp/core/view_projection.h"

namespace gasp::detail {

/// The constants computed once, for loops over many pixels.
struct PixelArea {
  ViewProjection projection;
  float min_cos;
  PixelArea(const ViewProjection& k, float min_cos_incidence) : projection(k), min_cos(min_cos_incidence) {}
  /// p: the point [m]; n: the surface normal (unit; zero counts as the clamped incidence).
  float operator()(const Eigen::Vector3f& p, const Eigen::Vector3f& n) const {
    const float frontal = projection.frontalArea(p);
    const float len = p.norm();
    // frontal / max(|n.p| / len, min_cos), with one division.
    return len > 0.0f ? frontal * len / std::max(std::abs(n.dot(p)), min_cos * len) : frontal;
  }
};

}  // namespace gasp::detail
