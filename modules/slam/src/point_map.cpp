#include "gasp/slam/point_map.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <iomanip>
#include <limits>

#include "gasp/core/error.h"
#include "gasp/core/output_file.h"
#include "gasp/core/point_cloud.h"
#include "gasp/core/undistortion.h"

namespace gasp {

VoxelPointMap::VoxelPointMap(double voxel_m, double max_depth_m) : voxel_m_(voxel_m), max_depth_m_(max_depth_m) {
  // The grid holds +-2^20 voxels per axis: +-1 km at the smallest voxel.
  if (!(voxel_m >= kMinVoxelM && voxel_m <= kMaxVoxelM))
    throw Error("point map: the voxel size must be from 0.001 to 10 m");
  if (!(max_depth_m > 0.0) || !std::isfinite(max_depth_m))
    throw Error("point map: the maximum depth must be positive and finite");
}

void VoxelPointMap::insert(const cv::Mat& depth_m, const CameraIntrinsics& intrinsics, const Isometry3& T_world_camera) {
  if (!T_world_camera.matrix().allFinite()) throw Error("point map: the pose is not finite");
  const auto [pinhole, k] = pinholeDepth(depth_m, intrinsics);
  const OrganizedPointCloud cloud = backProject(pinhole, k);
  const Eigen::Matrix3d R = T_world_camera.rotation();
  const Eigen::Vector3d t = T_world_camera.translation();
  for (const Eigen::Vector3f& pc : cloud.points) {
    if (!pc.allFinite() || pc.z() <= 0.0f || pc.z() > max_depth_m_) continue;
    add(R * pc.cast<double>() + t);
  }
}

void VoxelPointMap::insert(const RangeScan& scan, const Isometry3& T_world_sensor) {
  if (!T_world_sensor.matrix().allFinite()) throw Error("point map: the pose is not finite");
  validateLayout(scan, "point map");
  for (int r = 0; r < scan.range_m.rows; ++r)
    for (int c = 0; c < scan.range_m.cols; ++c) {
      const float range = scan.range_m.at<float>(r, c);
      if (!(range > 0.0f) || !std::isfinite(range) || range > max_depth_m_) continue;
      add(T_world_sensor * (static_cast<double>(range) * scan.direction(r, c)));
    }
}

void VoxelPointMap::add(const Eigen::Vector3d& p) {
  // 21 bits per axis: +-2^20 voxels (10 km at 1 cm).
  constexpr std::int64_t kHalf = std::int64_t{1} << 20, kMask = (std::int64_t{1} << 21) - 1;
  std::int64_t key = 0;
  for (int a = 0; a < 3; ++a) {
    const double cell = std::floor(p[a] / voxel_m_);
    if (!(std::abs(cell) < static_cast<double>(kHalf))) {  // also NaN; the cast below is then defined
      ++outside_;
      return;
    }
    const std::int64_t v = static_cast<std::int64_t>(cell) + kHalf;
    key = (key << 21) | (v & kMask);
  }
  Cell& c = voxels_[key];
  if (c.count == 0) c.order = voxels_.size() - 1;
  c.sum += p;
  ++c.count;
}

std::vector<Eigen::Vector3f> VoxelPointMap::points() const {
  std::vector<Eigen::Vector3f> out(voxels_.size());
  for (const auto& [key, c] : voxels_) out[c.order] = (c.sum / static_cast<double>(c.count)).cast<float>();
  return out;
}

void VoxelPointMap::writePly(const std::string& path) const {
  OutputFile file(path, "point cloud");
  writePly(file.stream());
  file.commit();
}

void VoxelPointMap::writePly(std::ostream& out) const {
  const auto precision = out.precision();
  const std::vector<Eigen::Vector3f> pts = points();
  out << "ply\nformat ascii 1.0\ncomment GASP point map, voxel " << voxel_m_ << " m\nelement vertex " << pts.size()
      << "\nproperty float x\nproperty float y\nproperty float z\nend_header\n";
  out << std::setprecision(std::numeric_limits<float>::max_digits10);
  for (const Eigen::Vector3f& p : pts) out << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
  out.precision(precision);
}

}  // namespace gasp
