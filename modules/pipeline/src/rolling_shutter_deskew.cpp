#include "gasp/pipeline/rolling_shutter_deskew.h"

#include <cmath>
#include <cstdio>
#include <tuple>
#include <utility>

#include "gasp/core/error.h"
#include "gasp/core/undistortion.h"

namespace gasp {

void validate(const DeskewParams& params) {
  // A frame is read out within its frame period; a second is far beyond any depth camera.
  if (!std::isfinite(params.readout_s) || std::abs(params.readout_s) > 1.0)
    throw Error("deskew: readout_s must be a finite time of at most 1 s (either sign)");
  if (!(params.max_speed_mps > 0.0) || !std::isfinite(params.max_speed_mps))
    throw Error("deskew: max_speed_mps must be positive");
  if (!(params.max_rate_radps > 0.0) || !std::isfinite(params.max_rate_radps))
    throw Error("deskew: max_rate_radps must be positive");
}

namespace {

/// The frame as it is (resampled to the pinhole camera), with the reason it was not deskewed.
DeskewOutcome notDeskewed(const cv::Mat& depth_m, const CameraIntrinsics& intrinsics, std::string reason) {
  DeskewOutcome out;
  std::tie(out.depth_m, out.intrinsics) = pinholeDepth(depth_m, intrinsics);
  out.reason = std::move(reason);
  return out;
}

}  // namespace

DeskewOutcome deskewWithNeighbours(const cv::Mat& depth_m, const CameraIntrinsics& intrinsics,
                                   const DepthView& before, const DepthView& after, double dt_s,
                                   const DeskewParams& params, const PairParams& pair) {
  validate(params);
  if (!(dt_s > 0.0) || !std::isfinite(dt_s)) throw Error("deskew: the neighbours' time step must be positive");
  if (params.readout_s == 0.0) return notDeskewed(depth_m, intrinsics, "no readout time");
  const PairResult r = registerViews(after, before, pair);  // T_before_after
  if (!r.pose.success) return notDeskewed(depth_m, intrinsics, "no pose between the neighbours: " + r.pose.reason);
  const CameraTwist twist = twistBetween(Isometry3::Identity(), r.pose.T_target_source, dt_s);
  if (!(twist.v_mps.norm() <= params.max_speed_mps) || !(twist.w_radps.norm() <= params.max_rate_radps)) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "implausible velocity between the neighbours: %.2f m/s, %.2f rad/s",
                  twist.v_mps.norm(), twist.w_radps.norm());
    return notDeskewed(depth_m, intrinsics, buf);
  }
  DeskewOutcome out = notDeskewed(depth_m, intrinsics, "");
  out.depth_m = deskewDepth(out.depth_m, out.intrinsics, twist, params.readout_s);
  out.deskewed = true;
  out.twist = twist;
  return out;
}

std::pair<std::size_t, std::size_t> neighbourFrames(std::size_t i, std::size_t n) {
  return {i > 0 ? i - 1 : i, i + 1 < n ? i + 1 : i};
}

DeskewOutcome deskewTumFrame(const TumDataset& ds, std::size_t i, const cv::Mat& depth_m,
                             const DeskewParams& params, const PairParams& pair) {
  validate(params);
  if (params.readout_s == 0.0) return notDeskewed(depth_m, ds.intrinsics(), "no readout time");
  const auto [a, b] = neighbourFrames(i, ds.size());
  if (a == b) return notDeskewed(depth_m, ds.intrinsics(), "no neighbouring frame");
  const auto [before, after] = makeDepthViews(ds.loadDepth(a), ds.loadDepth(b), ds.intrinsics(), pair.segment);
  return deskewWithNeighbours(depth_m, ds.intrinsics(), before, after, ds.frame(b).timestamp - ds.frame(a).timestamp,
                              params, pair);
}

}  // namespace gasp
