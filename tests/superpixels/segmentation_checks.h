#pragma once
// Checks shared by the superpixel tests.
#include <opencv2/core.hpp>

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

}  // namespace gasp::test
