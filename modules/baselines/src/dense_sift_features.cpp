#include "gasp/baselines/dense_sift_features.h"

#include <opencv2/features2d.hpp>

#include <chrono>
#include <cmath>

#include "gasp/core/error.h"
#include "gasp/core/stopwatch.h"
#include "pixel_keypoints.h"

namespace gasp::baselines {

void validate(const DenseSiftParams& p) {
  validate(p.surface);
  if (p.step_px < 1) throw Error("DenseSiftParams: step_px must be >= 1");
  if (p.scales.empty()) throw Error("DenseSiftParams: scales is empty");
  for (double s : p.scales)
    if (!(s > 0) || !std::isfinite(s)) throw Error("DenseSiftParams: scales must be finite and > 0");
}

DescribedKeypoints describeDenseSift(const RgbdImage& view, const DenseSiftParams& params) {
  validate(params);
  const auto t0 = std::chrono::steady_clock::now();
  const cv::Mat grey = greyImage(view, "dense SIFT");
  std::vector<cv::KeyPoint> keypoints;
  const float half = 0.5f * static_cast<float>(params.step_px);
  for (double s : params.scales)
    for (float v = half; v < static_cast<float>(grey.rows); v += static_cast<float>(params.step_px))
      for (float u = half; u < static_cast<float>(grey.cols); u += static_cast<float>(params.step_px)) {
        const float z = view.depth_m.at<float>(static_cast<int>(v), static_cast<int>(u));
        if (!(z > 0) || !(z <= params.surface.max_depth_m)) continue;  // no 3D point: not described
        keypoints.emplace_back(u, v, static_cast<float>(2.0 * s), 0.0f);  // size = 2 sigma, upright
      }
  cv::Mat descriptors;
  // compute() only: the keypoints are the grid (OpenCV keeps them all; octave 0 = original scale).
  cv::SIFT::create()->compute(grey, keypoints, descriptors);
  if (keypoints.empty()) descriptors.create(0, 128, CV_32F);
  DescribedKeypoints out = liftPixelKeypoints(view, keypoints, descriptors, params.surface);
  out.describe_ms = msSince(t0);
  return out;
}

}  // namespace gasp::baselines
