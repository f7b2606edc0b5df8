#pragma once
/// \file map_output.h The map outputs gasp-slam and gasp-graphslam share: --simplemap, --cloud,
/// --voxel, --cloud-max-depth, and writing them from scans at their optimised poses.
#include <CLI/CLI.hpp>

#include <string>
#include <utility>
#include <vector>

#include "gasp/core/pose.h"
#include "gasp/core/pose_perturbation.h"
#include "gasp/rawlog/rgbd_frame.h"
#include "run_outputs.h"

namespace gasp::tools {

struct MapOutputOptions {
  std::string simplemap_path;  ///< MRPT simple map to write; empty: none
  bool simplemap_points = false;  ///< the depth images' 3D points stored in the simple map too
  std::string cloud_path;      ///< voxel point cloud (PLY) to write; empty: none
  double voxel_m = 0.01;
  double cloud_max_depth_m = 4.0;
  /// True when a map is asked for (the scans must then be kept).
  bool wanted() const { return !simplemap_path.empty() || !cloud_path.empty(); }
};

/// Adds the five options; `scans` names what the map holds in the help ("keyframes", "nodes").
void addMapOutputOptions(CLI::App& app, MapOutputOptions& options, const std::string& scans);

/// The outputs of addMapOutputOptions(), for RunOutputs: {"--simplemap", path}, {"--cloud", path}.
std::vector<std::pair<std::string, std::string>> mapOutputPaths(const MapOutputOptions& options);

/// Writes what `options` asks for into `outputs`' "--simplemap" and "--cloud" files from
/// frames[i] at T_world_camera[i] and prints the lines "simplemap: PATH (N <scans>)" and "cloud:
/// PATH (N points, voxel V m)" (a warning on stderr for points beyond the voxel grid). The simple
/// map's poses carry covariance_world_camera[i] (keyframeSimpleMap()), zero when it is empty.
/// Throws gasp::Error when a file cannot be written.
void writeMapOutputs(const MapOutputOptions& options, RunOutputs& outputs, const std::vector<RgbdFrame>& frames,
                     const std::vector<Isometry3>& T_world_camera, const std::string& scans,
                     const std::vector<Matrix6>& covariance_world_camera = {});

}  // namespace gasp::tools
