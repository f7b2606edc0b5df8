#include "gasp/pipeline/rolling_shutter_deskew.h"

#include <cmath>
#include <cstdio>

#include "gasp/core/error.h"
#include "gasp/core/undistortion.h"

namespace gasp {

void validate(const DeskewParams& params) {
  if (!std::isfinite(params.readout_s)) throw Error("deskew: readout_s must be finite");
  if (!(params.max_speed_mps > 0.0) || !std::isfinite(params.max_speed_mps))
    throw Error("deskew: max_speed_mps must be positive");
  if (!(params.max_rate_radps > 0.0) || !std::isfinite(params.max_rate_radps))
    throw Error("deskew: max_rate_radps must be positive");
}

DeskewOutcome deskewWithNeighbours(const cv::Mat& depth_m, const CameraIntrinsics& intrinsics,
                                   const DepthView& before, const DepthView& after, double dt_s,
                                   const DeskewParams& params, const PairParams& pair) {
  validate(params);
  if (!(dt_s > 0.0) || !std::isfinite(dt_s)) throw Error("deskew: the neighbours' time step must be positive");
  DeskewOutcome out;
  out.depth_m = depth_m;
  out.intrinsics = intrinsics;
  if (hasLensDistortion(intrinsics)) {
    const auto undistortion = sharedUndistortion(intrinsics);
    out.depth_m = undistortion->applyToDepth(depth_m);
    out.intrinsics = undistortion->pinhole();
  }
  if (params.readout_s == 0.0) {
    out.reason = "no readout time";
    return out;
  }
  const PairResult r = registerViews(after, before, pair);  // T_before_after
  if (!r.pose.success) {
    out.reason = "no pose between the neighbours: " + r.pose.reason;
    return out;
  }
  const CameraTwist twist = twistBetween(Isometry3::Identity(), r.pose.T_target_source, dt_s);
  if (!(twist.v_mps.norm() <= params.max_speed_mps) || !(twist.w_radps.norm() <= params.max_rate_radps)) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "implausible velocity between the neighbours: %.2f m/s, %.2f rad/s",
                  twist.v_mps.norm(), twist.w_radps.norm());
    out.reason = buf;
    return out;
  }
  out.depth_m = deskewDepth(out.depth_m, out.intrinsics, twist, params.readout_s);
  out.deskewed = true;
  out.twist = twist;
  return out;
}

}  // namespace gasp
