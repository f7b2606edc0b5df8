#include "coarse_grid.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gasp::detail {

namespace {

/// Parameters in pixels scaled to cells of s x s pixels (lengths by s, counts by s^2).
SuperpixelParams scaledParams(const SuperpixelParams& p, int s) {
  auto length = [s](int px) { return std::max(1, static_cast<int>(std::lround(static_cast<double>(px) / s))); };
  auto count = [s](int px) { return std::max(1, static_cast<int>(std::lround(static_cast<double>(px) / (s * s)))); };
  SuperpixelParams c = p;
  c.processing_step_px = 1;
  c.surfaces.normal_window_px_per_m = p.surfaces.normal_window_px_per_m / s;
  c.surfaces.normal_min_radius_px = length(p.surfaces.normal_min_radius_px);
  c.surfaces.normal_max_radius_px = std::max(c.surfaces.normal_min_radius_px, length(p.surfaces.normal_max_radius_px));
  c.surfaces.min_component_pixels = count(p.surfaces.min_component_pixels);
  c.kmeans.seed_sampling_step_px = length(p.kmeans.seed_sampling_step_px);
  c.kmeans.kmeans_iteration_step_px = length(p.kmeans.kmeans_iteration_step_px);
  c.cleanup.min_patch_pixels = count(p.cleanup.min_patch_pixels);
  return c;
}

}  // namespace

CoarseGrid makeCoarseGrid(const OrganizedPointCloud& full, const CameraIntrinsics& k, const SuperpixelParams& p) {
  const int s = p.processing_step_px, w = full.width, h = full.height;
  CoarseGrid g;
  g.step = s;
  g.params = scaledParams(p, s);
  const int cw = (w + s - 1) / s, ch = (h + s - 1) / s;
  g.intrinsics = k;
  g.intrinsics.width = cw;
  g.intrinsics.height = ch;
  g.intrinsics.fx = k.fx / s;
  g.intrinsics.fy = k.fy / s;
  // Cell (c, r) is centred on full-resolution pixel (s c + (s - 1) / 2, s r + (s - 1) / 2).
  g.intrinsics.cx = (k.cx - 0.5 * (s - 1)) / s;
  g.intrinsics.cy = (k.cy - 0.5 * (s - 1)) / s;
  g.cloud.width = cw;
  g.cloud.height = ch;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  g.cloud.points.assign(static_cast<std::size_t>(cw) * ch, Eigen::Vector3f(nan, nan, nan));
  const float abs_m = static_cast<float>(p.surfaces.discontinuity_abs_m), rel = static_cast<float>(p.surfaces.discontinuity_rel);
  const Eigen::Vector3f* P = full.points.data();
  for (int r = 0; r < ch; ++r) {
    const int v0 = s * r, v1 = std::min(h, v0 + s);
    for (int c = 0; c < cw; ++c) {
      const int u0 = s * c, u1 = std::min(w, u0 + s);
      // The nearest valid depth of the block, then the mean of the points on its surface (the
      // link rule of depth_links.h). NaN (no depth) is neither the minimum nor within reach.
      float z_min = std::numeric_limits<float>::infinity();
      for (int v = v0; v < v1; ++v)
        for (int u = u0; u < u1; ++u) z_min = std::min(z_min, P[v * w + u].z());
      if (z_min == std::numeric_limits<float>::infinity()) continue;
      const float reach = abs_m + rel * z_min * z_min;
      float x = 0, y = 0, z = 0;
      int n = 0;
      for (int v = v0; v < v1; ++v)
        for (int u = u0; u < u1; ++u) {
          const Eigen::Vector3f& q = P[v * w + u];
          const bool on = q.z() - z_min <= reach;
          x += on ? q.x() : 0.0f, y += on ? q.y() : 0.0f, z += on ? q.z() : 0.0f, n += on;
        }
      g.cloud.points[static_cast<std::size_t>(r) * cw + c] = Eigen::Vector3f(x, y, z) / static_cast<float>(n);
    }
  }
  return g;
}

}  // namespace gasp::detail
