#pragma once
/// \file point_cloud.h Organised point cloud: one 3D point per depth pixel, in the camera frame.
#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

#include "gasp/core/camera_intrinsics.h"
#include "gasp/core/view_projection.h"

namespace gasp {

/// Row-major grid of points p_camera [m]; pixels without depth hold NaN in all three coordinates.
struct OrganizedPointCloud {
  int width = 0;
  int height = 0;
  std::vector<Eigen::Vector3f> points;  ///< size width * height, index v * width + u
  /// True for a range image's cloud: a point's depth (what its pixel holds, what discontinuities
  /// and windows are measured in) is its distance from the sensor, not its z.
  bool range_depth = false;

  float depth(const Eigen::Vector3f& p) const { return range_depth ? p.norm() : p.z(); }

  const Eigen::Vector3f& at(int u, int v) const { return points[static_cast<std::size_t>(v) * width + u]; }
  bool isValid(int u, int v) const { return at(u, v).allFinite(); }
  std::size_t countValid() const;
};

/// Back-projects a CV_32FC1 depth image [m] with the pinhole intrinsics (no undistortion).
/// Throws gasp::Error if the depth type is wrong or its size differs from the intrinsics'.
OrganizedPointCloud backProject(const cv::Mat& depth_m, const CameraIntrinsics& intrinsics);
/// The same with any projection: a spherical one's image holds ranges [m] along its cells' rays.
OrganizedPointCloud backProject(const cv::Mat& depth_m, const ViewProjection& projection);

}  // namespace gasp
