#include "gasp/core/undistortion.h"

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include <cmath>
#include <deque>
#include <mutex>
#include <utility>

#include "gasp/core/error.h"

namespace gasp {

bool hasLensDistortion(const CameraIntrinsics& k) {
  for (const double d : k.distortion)
    if (d != 0.0) return true;
  return false;
}

Undistortion::Undistortion(const CameraIntrinsics& k) : pinhole_(k) {
  k.validate();
  pinhole_.distortion.fill(0.0);
  if (!hasLensDistortion(k)) return;
  for (const double d : k.distortion)
    if (!std::isfinite(d)) throw Error("undistortion: the distortion coefficients must be finite");
  const cv::Matx33d K(k.fx, 0.0, k.cx, 0.0, k.fy, k.cy, 0.0, 0.0, 1.0);
  const cv::Mat dist(1, 5, CV_64F, const_cast<double*>(k.distortion.data()));
  cv::initUndistortRectifyMap(K, dist, cv::noArray(), K, cv::Size(k.width, k.height), CV_32FC1, map_x_, map_y_);
}

namespace {

void checkSize(const cv::Mat& image, const CameraIntrinsics& k, const char* what) {
  if (image.cols != k.width || image.rows != k.height)
    throw Error(std::string("undistortion: the ") + what + " is " + std::to_string(image.cols) + "x" +
                std::to_string(image.rows) + " but the intrinsics are for " + std::to_string(k.width) + "x" +
                std::to_string(k.height));
}

}  // namespace

std::shared_ptr<const Undistortion> sharedUndistortion(const CameraIntrinsics& k) {
  static std::mutex mutex;
  static std::deque<std::pair<CameraIntrinsics, std::shared_ptr<const Undistortion>>> cache;
  constexpr std::size_t kCapacity = 4;
  {
    const std::lock_guard<std::mutex> lock(mutex);
    for (const auto& [key, value] : cache)
      if (key == k) return value;
  }
  auto made = std::make_shared<const Undistortion>(k);  // outside the lock: may throw, takes ms
  const std::lock_guard<std::mutex> lock(mutex);
  cache.emplace_front(k, made);
  if (cache.size() > kCapacity) cache.pop_back();
  return made;
}

std::pair<cv::Mat, CameraIntrinsics> pinholeDepth(const cv::Mat& depth, const CameraIntrinsics& k) {
  if (!hasLensDistortion(k)) return {depth, k};
  const auto undistortion = sharedUndistortion(k);
  return {undistortion->applyToDepth(depth), undistortion->pinhole()};
}

cv::Mat Undistortion::applyToDepth(const cv::Mat& depth) const {
  if (depth.type() != CV_16UC1 && depth.type() != CV_32FC1)
    throw Error("undistortion: depth must be CV_16UC1 or CV_32FC1, got type " + std::to_string(depth.type()));
  checkSize(depth, pinhole_, "depth image");
  if (!active()) return depth;
  cv::Mat out;
  cv::remap(depth, out, map_x_, map_y_, cv::INTER_NEAREST, cv::BORDER_CONSTANT, cv::Scalar(0));
  return out;
}

cv::Mat Undistortion::applyToImage(const cv::Mat& image) const {
  if (image.empty()) return image;
  checkSize(image, pinhole_, "image");
  if (!active()) return image;
  cv::Mat out;
  cv::remap(image, out, map_x_, map_y_, cv::INTER_LINEAR, cv::BORDER_CONSTANT, cv::Scalar::all(0));
  return out;
}

}  // namespace gasp
