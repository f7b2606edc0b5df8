#include "gasp/superpixels/depth_links.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gasp {

namespace {

/// out[u] |= Bit where a[u] and b[u] are linked (NaN never is). Branch-free with a constant bit,
/// so it vectorises.
template <std::uint8_t Bit>
void linkRow(const float* __restrict a, const float* __restrict b, std::uint8_t* __restrict out, int n, float abs_m,
             float rel) {
  for (int u = 0; u < n; ++u) {
    const float lo = std::min(a[u], b[u]);
    const bool linked = std::abs(a[u] - b[u]) <= abs_m + rel * lo * lo;
    out[u] = static_cast<std::uint8_t>(out[u] | (linked ? Bit : 0));
  }
}

}  // namespace

DepthLinks::DepthLinks(const OrganizedPointCloud& cloud, const SuperpixelParams& p)
    : width_(cloud.width), height_(cloud.height), bits_(cloud.points.size(), 0) {
  const int w = width_, h = height_;
  // Depths as one flat array, NaN where invalid (backProject sets all three coordinates NaN).
  std::vector<float> z(static_cast<std::size_t>(w) * h);
  if (cloud.range_depth) {
    for (std::size_t i = 0; i < z.size(); ++i) z[i] = cloud.points[i].norm();
  } else {
    for (std::size_t i = 0; i < z.size(); ++i) z[i] = cloud.points[i].z();
  }
  std::size_t count = 0;
  for (std::size_t i = 0; i < z.size(); ++i) {
    const bool ok = std::abs(z[i]) <= std::numeric_limits<float>::max();  // finite: false for NaN, inf
    bits_[i] = ok ? kValid : 0;
    z[i] = ok ? z[i] : std::numeric_limits<float>::quiet_NaN();
    count += ok ? 1 : 0;
  }
  valid_count_ = count;
  const float abs_m = static_cast<float>(p.surfaces.discontinuity_abs_m), rel = static_cast<float>(p.surfaces.discontinuity_rel);
  for (int v = 0; v < h; ++v) {
    const float* zr = z.data() + static_cast<std::size_t>(v) * w;
    std::uint8_t* b = bits_.data() + static_cast<std::size_t>(v) * w;
    linkRow<kRight>(zr, zr + 1, b, w - 1, abs_m, rel);
    if (v + 1 < h) linkRow<kDown>(zr, zr + w, b, w, abs_m, rel);
  }
  // Interior: valid and linked on all four sides (image borders count as linked). Written to a
  // row buffer first: reading b[u - 1] while writing b[u] would serialise the loop.
  std::vector<std::uint8_t> inner(static_cast<std::size_t>(w));
  for (int v = 0; v < h; ++v) {
    std::uint8_t* __restrict b = bits_.data() + static_cast<std::size_t>(v) * w;
    const std::uint8_t* __restrict up = v > 0 ? b - w : b;
    const std::uint8_t up_ok = v > 0 ? 0 : kDown, down_ok = v + 1 < h ? 0 : kDown;
    std::uint8_t* __restrict out = inner.data();
    // Bit 0 of each shifted term: valid, right link, down link, left neighbour's right link, the
    // upper neighbour's down link.
    auto interior = [&](int u, std::uint8_t left, std::uint8_t right_ok) {
      const int ok = b[u] & ((b[u] | right_ok) >> 1) & ((b[u] | down_ok) >> 2) & (left >> 1) & ((up[u] | up_ok) >> 2);
      return static_cast<std::uint8_t>((ok & 1) << 3);
    };
    out[0] = interior(0, kRight, w > 1 ? 0 : kRight);
    for (int u = 1; u + 1 < w; ++u) out[u] = interior(u, b[u - 1], 0);
    if (w > 1) out[w - 1] = interior(w - 1, b[w - 2], kRight);
    for (int u = 0; u < w; ++u) b[u] = static_cast<std::uint8_t>(b[u] | out[u]);
  }
  static_assert(kValid == 1 && kRight == 2 && kDown == 4 && kInterior == 8, "bit positions used above");
}

}  // namespace gasp
