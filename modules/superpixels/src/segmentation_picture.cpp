#include "gasp/superpixels/segmentation_picture.h"

#include <algorithm>
#include <cmath>

#include "gasp/core/depth_image.h"
#include "gasp/core/error.h"

namespace gasp {

cv::Vec3b patchColour(int id) {
  // Golden-angle hue steps give neighbouring ids well-separated colours.
  const double hue = std::fmod(id * 137.508, 360.0);
  const double s = 0.55 + 0.35 * ((id * 7) % 3) / 2.0, val = 0.95;
  const double c = val * s, x = c * (1 - std::abs(std::fmod(hue / 60.0, 2.0) - 1)), m = val - c;
  double r = 0, g = 0, b = 0;
  switch (static_cast<int>(hue / 60.0)) {
    case 0: r = c; g = x; break;
    case 1: r = x; g = c; break;
    case 2: g = c; b = x; break;
    case 3: g = x; b = c; break;
    case 4: r = x; b = c; break;
    default: r = c; b = x; break;
  }
  auto to8 = [&](double t) { return static_cast<std::uint8_t>(std::lround((t + m) * 255.0)); };
  return {to8(b), to8(g), to8(r)};
}

cv::Mat drawSegmentation(const cv::Mat& depth_m, const SuperpixelSegmentation& seg) {
  if (depth_m.type() != CV_32FC1 || depth_m.size() != seg.labels.size())
    throw Error("drawSegmentation: depth must be CV_32FC1 of the label image's size");
  const int w = depth_m.cols, h = depth_m.rows;
  cv::Mat out(h, w, CV_8UC3, cv::Scalar(0, 0, 0));
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u) {
      const float z = depth_m.at<float>(v, u);
      if (!isValidDepth(z)) continue;
      // Shading from the depth gradient, so surfaces read as 3D under the colours.
      const float zr = u + 1 < w && isValidDepth(depth_m.at<float>(v, u + 1)) ? depth_m.at<float>(v, u + 1) : z;
      const float zd = v + 1 < h && isValidDepth(depth_m.at<float>(v + 1, u)) ? depth_m.at<float>(v + 1, u) : z;
      const float shade = std::clamp(0.75f + 40.0f * ((zr - z) + (zd - z)) / z, 0.35f, 1.0f);
      const int l = seg.labels.at<int>(v, u);
      bool border = false;
      if (l >= 0) {
        border = (u + 1 < w && seg.labels.at<int>(v, u + 1) != l) || (v + 1 < h && seg.labels.at<int>(v + 1, u) != l);
      }
      const cv::Vec3b base = l >= 0 ? patchColour(l) : cv::Vec3b(128, 128, 128);
      const float f = shade * (border ? 0.45f : 1.0f);
      out.at<cv::Vec3b>(v, u) = cv::Vec3b(static_cast<std::uint8_t>(base[0] * f), static_cast<std::uint8_t>(base[1] * f),
                                          static_cast<std::uint8_t>(base[2] * f));
    }
  return out;
}

}  // namespace gasp
