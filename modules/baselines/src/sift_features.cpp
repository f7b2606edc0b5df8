#include "gasp/baselines/sift_features.h"

#include <opencv2/features2d.hpp>

#include <chrono>

#include "gasp/core/error.h"
#include "gasp/core/stopwatch.h"
#include "pixel_keypoints.h"

namespace gasp::baselines {

void validate(const SiftParams& p) {
  validate(p.surface);
  if (p.max_features < 0) throw Error("SiftParams: max_features must be >= 0");
  if (!(p.contrast_threshold > 0)) throw Error("SiftParams: contrast_threshold must be > 0");
}

DescribedKeypoints describeSift(const RgbdImage& view, const SiftParams& params) {
  validate(params);
  const auto t0 = std::chrono::steady_clock::now();
  const cv::Mat grey = greyImage(view, "SIFT");
  auto sift = cv::SIFT::create(params.max_features, 3, params.contrast_threshold);
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
  sift->detectAndCompute(grey, cv::noArray(), keypoints, descriptors);
  if (keypoints.empty()) descriptors.create(0, 128, CV_32F);
  DescribedKeypoints out = liftPixelKeypoints(view, keypoints, descriptors, params.surface);
  out.describe_ms = msSince(t0);
  return out;
}

}  // namespace gasp::baselines
