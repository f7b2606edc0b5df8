#include "gasp/core/depth_image.h"

#include <opencv2/imgcodecs.hpp>

#include <fstream>
#include <limits>

#include "gasp/core/error.h"
#include "gasp/core/image_file.h"

namespace gasp {

namespace {
void checkScale(double units_per_metre) {
  if (!(std::isfinite(units_per_metre) && units_per_metre > 0.0))
    throw Error("depth scale (units per metre) must be positive, got " +
                std::to_string(units_per_metre));
}
}  // namespace

cv::Mat depthFromRaw(const cv::Mat& raw, double units_per_metre) {
  checkScale(units_per_metre);
  if (raw.type() != CV_16UC1)
    throw Error("raw depth must be a single-channel 16-bit image (CV_16UC1), got type " +
                std::to_string(raw.type()));
  cv::Mat depth;
  raw.convertTo(depth, CV_32F, 1.0 / units_per_metre);
  return depth;  // raw 0 stays 0 (invalid)
}

cv::Mat depthToRaw(const cv::Mat& depth_m, double units_per_metre) {
  checkScale(units_per_metre);
  if (depth_m.type() != CV_32FC1)
    throw Error("depth in metres must be CV_32FC1, got type " + std::to_string(depth_m.type()));
  cv::Mat raw(depth_m.size(), CV_16UC1);
  constexpr double kMax = std::numeric_limits<std::uint16_t>::max();
  for (int r = 0; r < depth_m.rows; ++r) {
    const float* in = depth_m.ptr<float>(r);
    auto* out = raw.ptr<std::uint16_t>(r);
    for (int c = 0; c < depth_m.cols; ++c) {
      const double units = isValidDepth(in[c]) ? std::round(in[c] * units_per_metre) : 0.0;
      out[c] = units <= kMax ? static_cast<std::uint16_t>(units) : 0;
    }
  }
  return raw;
}

cv::Mat loadDepthRaw(const std::string& path, int expected_width, int expected_height) {
  const cv::Mat img = readImage(path, cv::IMREAD_ANYDEPTH | cv::IMREAD_ANYCOLOR, "depth image");
  if (img.depth() != CV_16U)
    throw Error("depth image '" + path + "' must be 16-bit (got " +
                (img.depth() == CV_8U ? std::string("8-bit") : "type " + std::to_string(img.depth())) +
                ")");
  if (img.channels() != 1)
    throw Error("depth image '" + path + "' must have one channel, got " +
                std::to_string(img.channels()));
  if (expected_width > 0 && expected_height > 0 &&
      (img.cols != expected_width || img.rows != expected_height))
    throw Error("depth image '" + path + "' is " + std::to_string(img.cols) + "x" +
                std::to_string(img.rows) + ", expected " + std::to_string(expected_width) + "x" +
                std::to_string(expected_height) + " (the camera intrinsics' size)");
  return img;
}

cv::Mat loadDepth(const std::string& path, double units_per_metre, int expected_width,
                  int expected_height) {
  return depthFromRaw(loadDepthRaw(path, expected_width, expected_height), units_per_metre);
}

void saveDepth(const std::string& path, const cv::Mat& depth_m, double units_per_metre) {
  const cv::Mat raw = depthToRaw(depth_m, units_per_metre);
  writeImage(path, raw, "depth image");
}

std::size_t countValidDepth(const cv::Mat& depth_m) {
  if (depth_m.type() != CV_32FC1) throw Error("countValidDepth: depth must be CV_32FC1");
  std::size_t n = 0;
  for (int r = 0; r < depth_m.rows; ++r) {
    const float* p = depth_m.ptr<float>(r);
    for (int c = 0; c < depth_m.cols; ++c) n += isValidDepth(p[c]) ? 1 : 0;
  }
  return n;
}

}  // namespace gasp
