#include "gasp/odometry/odometry_params.h"

#include <cmath>
#include <string>

#include "gasp/core/error.h"

namespace gasp {

void validate(const OdometryParams& params) {
  requirePositive(params.keyframe_distance_m, "odometry: keyframe_distance_m");
  requirePositive(params.keyframe_angle_deg, "odometry: keyframe_angle_deg");
  requirePositive(params.max_speed_mps, "odometry: max_speed_mps");
  requirePositive(params.max_rate_radps, "odometry: max_rate_radps");
  if (!std::isfinite(params.rolling_shutter_readout_s) || std::abs(params.rolling_shutter_readout_s) > 1.0)
    throw Error("odometry: rolling_shutter_readout_s must be a finite time of at most 1 s (either sign)");
  validate(params.scene_change);
  validate(params.pair);
}

OdometryParams lidarOdometryParams(const LidarParams& lidar, const OdometryParams& base) {
  OdometryParams p = base;
  p.pair = lidarPairParams(lidar, base.pair);
  p.rolling_shutter_readout_s = 0.0;
  return p;
}

OdometryParams lidarOdometryParams(const LidarParams& lidar) {
  const OdometryParams defaults;
  return lidarOdometryParams(lidar, defaults);
}

}  // namespace gasp
