#pragma once
// gasp-simulate --sensor lidar16|lidar32|lidar64: the simulated sequence's path seen by a spinning
// LiDAR instead of the depth camera, written as an MRPT rawlog with its ground truth.
#include <string>

#include "gasp/sim/lidar.h"
#include "gasp/sim/simulation.h"

namespace gasp::tools {

struct LidarSequenceSummary {
  int sweeps = 0;
  double returns_per_sweep = 0.0;  ///< mean
  std::string rawlog, groundtruth;
};

/// Writes OUT/lidar.rawlog (one CObservationRotatingScan a frame, or with `as_point_clouds` one
/// CObservationPointCloud, sensor label "LIDAR", rawlog format #2) and OUT/lidar_groundtruth.txt (TUM trajectory of the LiDAR's frame, T_world_lidar: x
/// along the path's camera axis, z up its image), each whole or not at all; the camera sequence's
/// files are other names, so both can share a folder. The LiDAR's own noise only (options.noise
/// is the camera's and not used). With `sweep_motion` the sensor moves along the path during each
/// sweep (sim::simulateMovingLidarScan(), the path's pose at each column's time,
/// sim::poseAtTime()); the ground truth is each sweep's pose at its start, its timestamp. Throws
/// gasp::Error.
LidarSequenceSummary writeLidarSequence(const sim::SimulationOptions& options, const sim::LidarSensor& sensor,
                                        const std::string& out_dir, bool as_point_clouds = false,
                                        bool sweep_motion = false);

}  // namespace gasp::tools
