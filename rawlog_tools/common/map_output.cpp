#include "map_output.h"

#include <cstdio>

#include "cli.h"
#include "gasp/mrpt/keyframe_map.h"
#include "gasp/slam/point_map.h"

namespace gasp::tools {

void addMapOutputOptions(CLI::App& app, MapOutputOptions& o, const std::string& scans) {
  auto* simplemap = app.add_option("--simplemap", o.simplemap_path,
                                   "the " + scans + "' scans at their optimised poses as an MRPT simple map (for observations2map)");
  app.add_flag("--simplemap-points", o.simplemap_points,
               "store each depth image's 3D points in the simple map too, for MRPT's points maps (observations2map "
               "with pointsMap_count; about 3.7 MB more per 640x480 " + scans.substr(0, scans.size() - 1) +
                   "; a LiDAR's sweeps, where the program takes them, as 3D scans of their points)")
      ->needs(simplemap);
  app.add_option("--cloud", o.cloud_path, "a point map of the " + scans + "' scans at their optimised poses (PLY, one point per voxel)");
  app.add_option("--voxel", o.voxel_m, "voxel size of --cloud [m], 0.001 to 10")
      ->capture_default_str()
      ->check(within(kMinVoxelM, kMaxVoxelM));
  app.add_option("--cloud-max-depth", o.cloud_max_depth_m,
                 "depth (a LiDAR's: range) beyond which points are left out of --cloud [m]")
      ->capture_default_str()
      ->check(above(0));
}

std::vector<std::pair<std::string, std::string>> mapOutputPaths(const MapOutputOptions& o) {
  return {{"--simplemap", o.simplemap_path}, {"--cloud", o.cloud_path}};
}

void writeMapOutputs(const MapOutputOptions& o, RunOutputs& outputs, const std::vector<RgbdFrame>& frames,
                     const std::vector<Isometry3>& T_world_camera, const std::string& scans,
                     const std::vector<Matrix6>& covariance_world_camera) {
  if (!o.simplemap_path.empty()) {
    saveSimpleMap(keyframeSimpleMap(frames, T_world_camera, covariance_world_camera, o.simplemap_points),
                  outputs.at("--simplemap"));
    std::printf("simplemap: %s (%zu %s)\n", o.simplemap_path.c_str(), frames.size(), scans.c_str());
  }
  if (!o.cloud_path.empty()) {
    VoxelPointMap map(o.voxel_m, o.cloud_max_depth_m);
    for (std::size_t i = 0; i < frames.size() && i < T_world_camera.size(); ++i)
      if (frames[i].isSweep())
        map.insert(*frames[i].sweep, T_world_camera[i]);
      else
        map.insert(frames[i].depth_m, frames[i].depth_intrinsics, T_world_camera[i]);
    OutputFile& cloud = outputs.at("--cloud");
    map.writePly(cloud.stream());
    cloud.commit();
    std::printf("cloud: %s (%zu points, voxel %.3f m)\n", o.cloud_path.c_str(), map.size(), o.voxel_m);
    if (map.pointsOutside() > 0)
      std::fprintf(stderr, "warning: %zu points lie beyond the voxel grid (+-2^20 voxels) and are not in the cloud\n",
                   map.pointsOutside());
  }
}

}  // namespace gasp::tools
