#pragma once
/// \file point_map.h A point map of the scene from depth images (or LiDAR sweeps) at their poses:
/// the union of their back-projected points, thinned to one point per voxel (the mean of its
/// points).
#include <Eigen/Core>
#include <opencv2/core.hpp>

#include <cstddef>
#include <cstdint>
#include <ostream>
#include <string>
#include <unordered_map>
#include <vector>

#include "gasp/core/camera_intrinsics.h"
#include "gasp/core/range_scan.h"
#include "gasp/core/pose.h"

namespace gasp {

/// Voxel sizes a VoxelPointMap accepts [m].
constexpr double kMinVoxelM = 0.001;
constexpr double kMaxVoxelM = 10.0;

class VoxelPointMap {
 public:
  /// Throws gasp::Error unless voxel_m is within [kMinVoxelM, kMaxVoxelM] and max_depth_m
  /// positive and finite.
  explicit VoxelPointMap(double voxel_m = 0.01, double max_depth_m = 4.0);

  /// Adds a depth image [m] (CV_32FC1, 0 or NaN = no data; lens distortion in the intrinsics is
  /// resampled away) seen from T_world_camera; points farther than max_depth_m are left out
  /// (the Kinect's depth noise grows with the square of the depth). Throws gasp::Error for a
  /// wrong image type or size, or a non-finite pose.
  void insert(const cv::Mat& depth_m, const CameraIntrinsics& intrinsics, const Isometry3& T_world_camera);
  /// Adds a rotating LiDAR's sweep (range_scan.h) seen from T_world_sensor: each return along its
  /// cell's ray; returns farther than max_depth_m are left out. Throws gasp::Error for a scan
  /// without a layout (validateLayout) or a non-finite pose.
  void insert(const RangeScan& scan, const Isometry3& T_world_sensor);

  std::size_t size() const { return voxels_.size(); }
  /// Points left out because they lie beyond the grid (+-2^20 voxels per axis from the origin).
  std::size_t pointsOutside() const { return outside_; }
  /// One point per occupied voxel, the mean of the points in it [m], in insertion order of the voxels.
  std::vector<Eigen::Vector3f> points() const;
  /// Writes the points as an ASCII PLY (x y z float vertices), whole or not at all
  /// (gasp/core/output_file.h). Throws gasp::Error when it cannot.
  void writePly(const std::string& path) const;
  /// The same into a stream; the caller checks it.
  void writePly(std::ostream& out) const;

 private:
  struct Cell {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    std::size_t count = 0;
    std::size_t order = 0;
  };
  void add(const Eigen::Vector3d& p_world);  ///< into its voxel, or counted outside the grid

  double voxel_m_;
  double max_depth_m_;
  std::unordered_map<std::int64_t, Cell> voxels_;
  std::size_t outside_ = 0;
};

}  // namespace gasp
