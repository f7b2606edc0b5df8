#include "deskew_filter.h"

#include <chrono>
#include <cstdio>

#include "gasp/core/rolling_shutter.h"
#include "gasp/core/stopwatch.h"
#include "gasp/core/tum_trajectory.h"

namespace gasp::pairs {

cv::Mat DeskewFilter::operator()(std::size_t i, const cv::Mat& depth_m) {
  frames_.insert(i);
  if (from_ == TwistFrom::kTruth) {
    // The reference samples nearest to 20 ms either side, and the time between them.
    const double t = ds_.frame(i).timestamp + offset_s_;
    const auto& gt = ds_.groundTruth();
    const auto a = findNearest(gt, t - 0.02, 0.02), b = findNearest(gt, t + 0.02, 0.02);
    if (!a || !b || *a == *b) return depth_m;
    deskewed_.insert(i);
    return deskewDepth(depth_m, ds_.intrinsics(),
                       twistBetween(gt[*a].T_world_camera, gt[*b].T_world_camera, gt[*b].timestamp - gt[*a].timestamp),
                       deskew_.readout_s);
  }
  const auto t0 = std::chrono::steady_clock::now();
  auto out = deskewTumFrame(ds_, i, depth_m, deskew_, params_);
  ms_.push_back(msSince(t0));
  if (!out.deskewed) {
    std::fprintf(stderr, "frame %zu not deskewed: %s\n", i, out.reason.c_str());
    return depth_m;
  }
  deskewed_.insert(i);
  return out.depth_m;
}

}  // namespace gasp::pairs
