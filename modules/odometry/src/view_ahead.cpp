#include "gasp/odometry/view_ahead.h"

#include <chrono>
#include <exception>

#include "gasp/core/stopwatch.h"

namespace gasp {

ViewAhead::ViewAhead(const OdometryParams& params, bool enabled)
    : superpixels_(params.pair.segment), enabled_(enabled && params.rolling_shutter_readout_s == 0.0) {}

ViewAhead::~ViewAhead() {
  if (pending_.valid()) pending_.wait();
}

void ViewAhead::start(const cv::Mat& depth_m, const CameraIntrinsics& intrinsics) {
  if (pending_.valid()) pending_.wait();
  pending_ = {};
  // A depth image addFrame() would refuse is not segmented here: addFrame() says why.
  if (!enabled_ || depth_m.empty() || depth_m.type() != CV_32FC1 || depth_m.cols != intrinsics.width ||
      depth_m.rows != intrinsics.height)
    return;
  pending_ = std::async(std::launch::async, [depth_m, intrinsics, superpixels = superpixels_] {
    const auto t0 = std::chrono::steady_clock::now();
    SegmentedDepth s;
    s.view = makeDepthView(depth_m, intrinsics, superpixels);
    s.ms = msSince(t0);
    return s;
  });
}

std::optional<SegmentedDepth> ViewAhead::take() {
  if (!pending_.valid()) return std::nullopt;
  try {
    return pending_.get();
  } catch (const std::exception&) {
    return std::nullopt;  // addFrame() segments again and reports the error itself
  }
}

}  // namespace gasp
