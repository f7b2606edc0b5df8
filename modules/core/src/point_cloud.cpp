#include "gasp/core/point_cloud.h"

#include <limits>

#include "gasp/core/depth_image.h"
#include "gasp/core/error.h"

namespace gasp {

std::size_t OrganizedPointCloud::countValid() const {
  std::size_t n = 0;
  for (const auto& p : points) n += p.allFinite() ? 1 : 0;
  return n;
}

OrganizedPointCloud backProject(const cv::Mat& depth_m, const CameraIntrinsics& k) {
  k.validate();
  if (depth_m.type() != CV_32FC1)
    throw Error("backProject: depth must be CV_32FC1 in metres, got type " +
                std::to_string(depth_m.type()));
  if (depth_m.cols != k.width || depth_m.rows != k.height)
    throw Error("backProject: depth is " + std::to_string(depth_m.cols) + "x" +
                std::to_string(depth_m.rows) + " but the intrinsics are for " +
                std::to_string(k.width) + "x" + std::to_string(k.height));
  OrganizedPointCloud cloud;
  cloud.width = k.width;
  cloud.height = k.height;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  cloud.points.assign(static_cast<std::size_t>(k.width) * k.height, Eigen::Vector3f(nan, nan, nan));
  const float inv_fx = static_cast<float>(1.0 / k.fx), inv_fy = static_cast<float>(1.0 / k.fy);
  const float cx = static_cast<float>(k.cx), cy = static_cast<float>(k.cy);
  for (int v = 0; v < k.height; ++v) {
    const float* row = depth_m.ptr<float>(v);
    for (int u = 0; u < k.width; ++u) {
      const float z = row[u];
      if (!isValidDepth(z)) continue;
      cloud.points[static_cast<std::size_t>(v) * k.width + u] =
          Eigen::Vector3f((static_cast<float>(u) - cx) * z * inv_fx,
                          (static_cast<float>(v) - cy) * z * inv_fy, z);
    }
  }
  return cloud;
}

OrganizedPointCloud backProject(const cv::Mat& depth_m, const ViewProjection& projection) {
  if (projection.isPinhole()) return backProject(depth_m, projection.pinhole());
  const int w = projection.width(), h = projection.height();
  if (depth_m.type() != CV_32FC1)
    throw Error("backProject: a range image must be CV_32FC1 in metres, got type " + std::to_string(depth_m.type()));
  if (depth_m.cols != w || depth_m.rows != h)
    throw Error("backProject: the range image is " + std::to_string(depth_m.cols) + "x" + std::to_string(depth_m.rows) +
                " but its grid is " + std::to_string(w) + "x" + std::to_string(h));
  OrganizedPointCloud cloud;
  cloud.width = w;
  cloud.height = h;
  cloud.range_depth = true;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  cloud.points.assign(static_cast<std::size_t>(w) * h, Eigen::Vector3f(nan, nan, nan));
  for (int v = 0; v < h; ++v) {
    const float* row = depth_m.ptr<float>(v);
    for (int u = 0; u < w; ++u)
      if (isValidDepth(row[u]))
        cloud.points[static_cast<std::size_t>(v) * w + u] = (row[u] * projection.ray(u, v)).cast<float>();
  }
  return cloud;
}

}  // namespace gasp
