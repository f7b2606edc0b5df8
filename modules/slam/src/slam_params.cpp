#include "gasp/slam/slam_params.h"

#include <cmath>
#include <string>

#include "gasp/core/error.h"

namespace gasp {

void validate(const LoopClosureParams& p) {
  requirePositive(p.search_radius_m, "loop closure: search_radius_m");
  requirePositive(p.max_axis_angle_deg, "loop closure: max_axis_angle_deg");
  requirePositive(p.gate_chi2, "loop closure: gate_chi2");
  if (p.min_keyframe_gap < 1) throw Error("loop closure: min_keyframe_gap must be at least 1");
  if (p.min_inliers < 3 || p.relocalisation_min_inliers < 3)
    throw Error("loop closure: min_inliers and relocalisation_min_inliers must be at least 3");
  if (p.relocalisation_agreeing < 1 || p.relocalisation_agreeing > LoopClosureParams::kMaxRelocalisationAgreeing)
    throw Error("loop closure: relocalisation_agreeing must be from 1 to " +
                std::to_string(LoopClosureParams::kMaxRelocalisationAgreeing));
}

void validate(const SlamParams& p) {
  validate(p.odometry);
  validate(p.loop);
  validate(p.graph);
  validate(p.lidar);
}

SlamParams lidarSlamParams(const SlamParams& params) {
  SlamParams p = params;
  p.odometry = lidarOdometryParams(params.lidar, params.odometry);
  return p;
}

}  // namespace gasp
