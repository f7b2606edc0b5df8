#pragma once
// Surface area seen by one pixel: (z^2 / (fx fy)) / cos(incidence), the incidence clamped.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>

#include "gasp/core/camera_intrinsics.h"

namespace gasp::detail {

inline float pixelArea(const Eigen::Vector3f& p, const Eigen::Vector3f& n, const CameraIntrinsics& k,
                       float min_cos) {
  const float z = p.z();
  const float frontal = z * z / static_cast<float>(k.fx * k.fy);
  const float len = p.norm();
  const float cos_inc = len > 0.0f ? std::abs(n.dot(p)) / len : 1.0f;
  return frontal / std::max(cos_inc, min_cos);
}

}  // namespace gasp::detail
