#include "gasp/odometry/view_ahead.h"

#include <chrono>
#include <exception>

#include "gasp/core/stopwatch.h"
#include "gasp/pipeline/range_view.h"

namespace gasp {

ViewAhead::ViewAhead(const OdometryParams& params, bool enabled)
    : superpixels_(params.pair.segment),
      returns_(params.pair.returns),
      enabled_(enabled && params.rolling_shutter_readout_s == 0.0),
      deskew_sweeps_(params.deskew_sweeps) {}

ViewAhead::~ViewAhead() {
  for (auto& f : pending_)
    if (f.valid()) f.wait();
}

void ViewAhead::start(const cv::Mat& depth_m, const CameraIntrinsics& intrinsics) {
  if (!enabled_) return;
  // A depth image addFrame() would refuse is not segmented here: addFrame() says why. Its place
  // in the queue is kept, so that later takes stay with their frames.
  if (depth_m.empty() || depth_m.type() != CV_32FC1 || depth_m.cols != intrinsics.width ||
      depth_m.rows != intrinsics.height) {
    pending_.emplace_back();
    return;
  }
  pending_.push_back(std::async(std::launch::async, [depth_m, intrinsics, superpixels = superpixels_] {
    const auto t0 = std::chrono::steady_clock::now();
    SegmentedDepth s;
    s.view = makeDepthView(depth_m, intrinsics, superpixels);
    s.ms = msSince(t0);
    return s;
  }));
}

void ViewAhead::start(const RangeScan& sweep) {
  if (!enabled_) return;
  // A sweep the odometry may deskew is segmented there; its place in the queue is kept.
  if (deskew_sweeps_ && sweepTimed(sweep)) {
    pending_.emplace_back();
    return;
  }
  // A scan makeRangeView() refuses fails here too: take() is then empty and addFrame() says why.
  pending_.push_back(std::async(std::launch::async, [sweep, superpixels = superpixels_, returns = returns_] {
    const auto t0 = std::chrono::steady_clock::now();
    SegmentedDepth s;
    s.view = makeRangeView(sweep, superpixels, returns);
    s.ms = msSince(t0);
    return s;
  }));
}

std::optional<SegmentedDepth> ViewAhead::take() {
  if (pending_.empty()) return std::nullopt;
  std::future<SegmentedDepth> oldest = std::move(pending_.front());
  pending_.pop_front();
  if (!oldest.valid()) return std::nullopt;
  try {
    return oldest.get();
  } catch (const std::exception&) {
    return std::nullopt;  // addFrame() segments again and reports the error itself
  }
}

}  // namespace gasp
