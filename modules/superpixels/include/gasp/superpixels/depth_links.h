#pragma once
/// \file depth_links.h Which neighbouring pixels lie on one surface, decided once per image: two
/// 4-neighbours with valid depth are linked when |z1 - z2| <= discontinuity_abs_m +
/// discontinuity_rel * min(z1, z2)^2 (Kinect depth steps grow with z^2). Every later stage asks
/// these links instead of comparing depths again.
#include <cstdint>
#include <vector>

#include "gasp/core/point_cloud.h"
#include "gasp/superpixels/superpixel_params.h"

namespace gasp {

/// True when two depths [m] of neighbouring pixels belong to one surface.
inline bool depthConnected(float z1, float z2, const SuperpixelParams& p) {
  const float z = z1 < z2 ? z1 : z2;
  const float d = z1 > z2 ? z1 - z2 : z2 - z1;
  return d <= static_cast<float>(p.surfaces.discontinuity_abs_m + p.surfaces.discontinuity_rel * z * z);
}

class DepthLinks {
 public:
  DepthLinks(const OrganizedPointCloud& cloud, const SuperpixelParams& params);

  int width() const { return width_; }
  int height() const { return height_; }
  std::size_t validCount() const { return valid_count_; }  ///< pixels with valid depth
  bool valid(int i) const { return bits_[static_cast<std::size_t>(i)] & kValid; }
  bool right(int i) const { return bits_[static_cast<std::size_t>(i)] & kRight; }  ///< i and i + 1
  bool down(int i) const { return bits_[static_cast<std::size_t>(i)] & kDown; }    ///< i and i + width
  /// Valid and linked to every valid 4-neighbour, with no invalid 4-neighbour.
  bool interior(int i) const { return bits_[static_cast<std::size_t>(i)] & kInterior; }

  /// Calls fn(a, b) for every linked pair (each once, b = a + 1 or a + width).
  template <typename Fn>
  void forEachLink(Fn fn) const {
    const int n = width_ * height_;
    for (int i = 0; i < n; ++i) {
      const std::uint8_t b = bits_[static_cast<std::size_t>(i)];
      if (b & kRight) fn(i, i + 1);
      if (b & kDown) fn(i, i + width_);
    }
  }
  /// The raw bits of pixel i (kValid | kRight | kDown | kInterior), for tight loops.
  std::uint8_t bits(int i) const { return bits_[static_cast<std::size_t>(i)]; }
  static constexpr std::uint8_t kValid = 1, kRight = 2, kDown = 4, kInterior = 8;
  /// Calls fn(j) for every pixel j linked to pixel i.
  template <typename Fn>
  void forEachNeighbour(int i, Fn fn) const {
    if (right(i)) fn(i + 1);
    if (down(i)) fn(i + width_);
    if (i > 0 && right(i - 1)) fn(i - 1);  // the last pixel of a row has no right link
    if (i >= width_ && down(i - width_)) fn(i - width_);
  }

 private:
  int width_ = 0, height_ = 0;
  std::size_t valid_count_ = 0;
  std::vector<std::uint8_t> bits_;
};

}  // namespace gasp
