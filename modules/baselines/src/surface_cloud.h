#pragma once
// Private: the downsampled surface cloud with normals (surface_params.h), in PCL types.
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/search/kdtree.h>

#include <vector>

#include "gasp/baselines/rgbd_image.h"
#include "gasp/baselines/surface_params.h"

namespace gasp::baselines {

using SurfacePoint = pcl::PointXYZRGBA;

struct SurfaceCloud {
  pcl::PointCloud<SurfacePoint>::Ptr points{new pcl::PointCloud<SurfacePoint>};
  pcl::PointCloud<pcl::Normal>::Ptr normals{new pcl::PointCloud<pcl::Normal>};
  pcl::search::KdTree<SurfacePoint>::Ptr tree{new pcl::search::KdTree<SurfacePoint>};  ///< over points
};

/// The view's surface cloud (validates view and params). Empty when the view has no valid depth.
SurfaceCloud makeSurfaceCloud(const RgbdImage& view, const SurfaceParams& params);
/// The same from points in a sensor frame (a LiDAR sweep's returns; no colour): those within
/// max_depth_m of the sensor, normals facing it.
SurfaceCloud makeSurfaceCloud(const std::vector<Eigen::Vector3f>& points, const SurfaceParams& params);

/// Index of the surface point nearest p within max_distance_m whose normal is finite, or -1.
int nearestWithNormal(const SurfaceCloud& surface, const Eigen::Vector3f& p, double max_distance_m);

}  // namespace gasp::baselines
