#pragma once
// Checks shared by the superpixel tests.
#include <opencv2/core.hpp>

#include <algorithm>
#include <cstdint>
#include <map>
#include <queue>
#include <vector>

#include "gasp/superpixels/surface_patch.h"

namespace gasp::test {

/// Number of patches whose pixels do not form one 4-connected region of the label image.
inline int countNonContiguousPatches(const SuperpixelSegmentation& seg) {
  const int w = seg.labels.cols, h = seg.labels.rows;
  std::vector<int> pieces(seg.patches.size(), 0);
  cv::Mat seen(h, w, CV_8U, cv::Scalar(0));
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u) {
      const int l = seg.labels.at<int>(v, u);
      if (l < 0 || seen.at<std::uint8_t>(v, u)) continue;
      ++pieces[static_cast<std::size_t>(l)];
      std::queue<cv::Point> q;
      q.push({u, v});
      seen.at<std::uint8_t>(v, u) = 1;
      while (!q.empty()) {
        const cv::Point p = q.front();
        q.pop();
        const cv::Point nb[4] = {{p.x + 1, p.y}, {p.x - 1, p.y}, {p.x, p.y + 1}, {p.x, p.y - 1}};
        for (const auto& n : nb) {
          if (n.x < 0 || n.y < 0 || n.x >= w || n.y >= h) continue;
          if (seen.at<std::uint8_t>(n) || seg.labels.at<int>(n) != l) continue;
          seen.at<std::uint8_t>(n) = 1;
          q.push(n);
        }
      }
    }
  int bad = 0;
  for (int c : pieces) bad += c != 1;
  return bad;
}

/// How well patches keep to ground-truth surfaces (surface_ids: CV_16UC1, one id per pixel).
struct SurfacePurity {
  int patches_on_one_surface = 0;  ///< patches with >= 90% of their pixels on one surface
  int patches = 0;
  int pixels_off_majority = 0;  ///< pixels on another surface than their patch's majority
  /// Share of the patches on one surface (0 without patches).
  double shareOnOneSurface() const {
    return patches > 0 ? static_cast<double>(patches_on_one_surface) / static_cast<double>(patches) : 0.0;
  }
};

inline SurfacePurity surfacePurity(const SuperpixelSegmentation& seg, const cv::Mat& surface_ids) {
  std::vector<std::map<int, int>> votes(seg.patches.size());
  for (int v = 0; v < seg.labels.rows; ++v)
    for (int u = 0; u < seg.labels.cols; ++u) {
      const int l = seg.labels.at<int>(v, u);
      if (l >= 0) ++votes[static_cast<std::size_t>(l)][surface_ids.at<std::uint16_t>(v, u)];
    }
  SurfacePurity out;
  int pure = 0;
  for (std::size_t i = 0; i < votes.size(); ++i) {
    int best = 0;
    for (const auto& [surface, n] : votes[i]) best = std::max(best, n);
    pure += best >= 0.9 * seg.patches[i].pixel_count;
    out.pixels_off_majority += seg.patches[i].pixel_count - best;
  }
  out.patches_on_one_surface = pure;
  out.patches = static_cast<int>(votes.size());
  return out;
}

}  // namespace gasp::test
