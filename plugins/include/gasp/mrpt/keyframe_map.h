#pragma once
/// \file keyframe_map.h A map built offline by GASP's SLAM as MRPT consumes it: the keyframes'
/// scans at their optimised poses in an mrpt::maps::CSimpleMap, from which MRPT's own tools
/// build metric maps (observations2map: point maps, octomaps, occupancy grids).
#include <mrpt/maps/CSimpleMap.h>

#include <string>
#include <vector>

#include "gasp/core/pose.h"
#include "gasp/rawlog/rgbd_frame.h"

namespace gasp {

/// One (pose, sensory frame) pair per keyframe: the robot's pose T_world_camera[i]
/// T_robot_camera^-1 (T_robot_camera = the frame's own, MRPT's sensorPose), as a
/// CPose3DPDFGaussian with a zero covariance (the graph's marginals are not computed), and a
/// sensory frame holding the scan (observationFromFrame()). Throws gasp::Error when the sizes
/// differ or a frame cannot be converted.
mrpt::maps::CSimpleMap keyframeSimpleMap(const std::vector<RgbdFrame>& keyframes,
                                         const std::vector<Isometry3>& T_world_camera);

/// Writes the map with MRPT's serialization (CSimpleMap::saveToFile, gzip-compressed as MRPT's
/// own .simplemap files). Throws gasp::Error when it cannot be written.
void saveSimpleMap(const mrpt::maps::CSimpleMap& map, const std::string& path);

}  // namespace gasp
