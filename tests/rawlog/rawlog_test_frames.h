#pragma once
// Synthetic RGB-D frames for the rawlog tests that must run without the real data.
#include <opencv2/core.hpp>

#include "gasp/core/depth_image.h"
#include "gasp/rawlog/rgbd_frame.h"

namespace gasp::test {

/// A small frame: every pixel valid (slanted, ~1..3 m, in 1/5000 m units), a colour
/// gradient, ROS-like intrinsics scaled to the size, timestamp t.
inline RgbdFrame syntheticFrame(double t, int width = 64, int height = 48) {
  RgbdFrame f;
  f.timestamp = t;
  f.depth_intrinsics.width = width;
  f.depth_intrinsics.height = height;
  f.depth_intrinsics.fx = 52.5;
  f.depth_intrinsics.fy = 53.0;
  f.depth_intrinsics.cx = 31.5;
  f.depth_intrinsics.cy = 23.7;
  f.depth_raw = cv::Mat(height, width, CV_16UC1);
  f.rgb = cv::Mat(height, width, CV_8UC3);
  for (int v = 0; v < height; ++v)
    for (int u = 0; u < width; ++u) {
      f.depth_raw.at<std::uint16_t>(v, u) = static_cast<std::uint16_t>(
          5001 + 6000 * u / width + 4000 * v / height + (u * 7 + v * 13) % 17);
      f.rgb.at<cv::Vec3b>(v, u) = cv::Vec3b(static_cast<uchar>(4 * u), static_cast<uchar>(5 * v),
                                            static_cast<uchar>((u + v) % 256));
    }
  f.depth_units_per_metre = kTumDepthUnitsPerMetre;
  f.depth_m = depthFromRaw(f.depth_raw, f.depth_units_per_metre);
  f.rgb_intrinsics = f.depth_intrinsics;
  f.rgb_intrinsics.fx = 60.0;
  return f;
}

/// True when two matrices have the same size, type and every element equal.
inline bool sameMat(const cv::Mat& a, const cv::Mat& b) {
  if (a.empty() || b.empty()) return a.empty() && b.empty();  // release() keeps the type
  if (a.size() != b.size() || a.type() != b.type()) return false;
  cv::Mat diff;
  cv::compare(a.reshape(1), b.reshape(1), diff, cv::CMP_NE);
  return cv::countNonZero(diff) == 0;
}

}  // namespace gasp::test
