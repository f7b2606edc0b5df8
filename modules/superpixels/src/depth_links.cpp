#include "gasp/superpixels/depth_links.h"

namespace gasp {

DepthLinks::DepthLinks(const OrganizedPointCloud& cloud, const SuperpixelParams& p)
    : width_(cloud.width), height_(cloud.height), bits_(cloud.points.size(), 0) {
  const int w = width_, h = height_;
  for (int i = 0; i < w * h; ++i)
    if (cloud.points[static_cast<std::size_t>(i)].allFinite()) bits_[static_cast<std::size_t>(i)] = kValid;
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u) {
      const int i = v * w + u;
      if (!valid(i)) continue;
      const float z = cloud.points[static_cast<std::size_t>(i)].z();
      if (u + 1 < w && valid(i + 1) && depthConnected(z, cloud.points[static_cast<std::size_t>(i) + 1].z(), p))
        bits_[static_cast<std::size_t>(i)] |= kRight;
      if (v + 1 < h && valid(i + w) && depthConnected(z, cloud.points[static_cast<std::size_t>(i + w)].z(), p))
        bits_[static_cast<std::size_t>(i)] |= kDown;
    }
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u) {
      const int i = v * w + u;
      if (!valid(i)) continue;
      const bool ok = (u + 1 >= w || right(i)) && (v + 1 >= h || down(i)) && (u == 0 || right(i - 1)) &&
                      (v == 0 || down(i - w));
      if (ok) bits_[static_cast<std::size_t>(i)] |= kInterior;
    }
}

}  // namespace gasp
