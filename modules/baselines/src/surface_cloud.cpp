#include "surface_cloud.h"

#include <pcl/features/normal_3d_omp.h>
#include <pcl/filters/voxel_grid.h>

#include <cmath>

#include "gasp/core/error.h"

namespace gasp::baselines {

void validate(const SurfaceParams& p) {
  if (!(p.voxel_m > 0) || !std::isfinite(p.voxel_m)) throw Error("SurfaceParams: voxel_m must be finite and > 0");
  if (!(p.normal_radius_m > p.voxel_m) || !std::isfinite(p.normal_radius_m))
    throw Error("SurfaceParams: normal_radius_m must be finite and > voxel_m");
  if (!(p.max_depth_m > 0)) throw Error("SurfaceParams: max_depth_m must be > 0");
  if (p.threads < 0) throw Error("SurfaceParams: threads must be >= 0");
}

namespace {

/// Voxel grid, normals facing the sensor at the origin, points without a normal dropped.
SurfaceCloud surfaceOf(const pcl::PointCloud<SurfacePoint>::Ptr& raw, const SurfaceParams& params) {
  SurfaceCloud s;
  if (raw->empty()) return s;
  pcl::VoxelGrid<SurfacePoint> grid;
  grid.setInputCloud(raw);
  const auto leaf = static_cast<float>(params.voxel_m);
  grid.setLeafSize(leaf, leaf, leaf);
  grid.setDownsampleAllData(true);  // average the colour too
  grid.filter(*s.points);
  s.tree->setInputCloud(s.points);

  pcl::NormalEstimationOMP<SurfacePoint, pcl::Normal> ne(static_cast<unsigned>(params.threads));
  ne.setInputCloud(s.points);
  ne.setSearchMethod(s.tree);
  ne.setRadiusSearch(params.normal_radius_m);
  ne.setViewPoint(0.0f, 0.0f, 0.0f);  // the camera: normals face it
  pcl::PointCloud<pcl::Normal> normals;
  ne.compute(normals);
  // Points without a normal (too few neighbours) are dropped, so every descriptor's support has
  // normals everywhere.
  pcl::PointCloud<SurfacePoint>::Ptr kept(new pcl::PointCloud<SurfacePoint>);
  for (std::size_t i = 0; i < normals.size(); ++i) {
    const auto& n = normals[i];
    if (!std::isfinite(n.normal_x) || !std::isfinite(n.normal_y) || !std::isfinite(n.normal_z)) continue;
    kept->push_back((*s.points)[i]);
    s.normals->push_back(n);
  }
  s.points = kept;
  s.tree->setInputCloud(s.points);
  return s;
}

}  // namespace

SurfaceCloud makeSurfaceCloud(const std::vector<Eigen::Vector3f>& points, const SurfaceParams& params) {
  validate(params);
  pcl::PointCloud<SurfacePoint>::Ptr raw(new pcl::PointCloud<SurfacePoint>);
  raw->reserve(points.size());
  for (const Eigen::Vector3f& p : points) {
    const float range = p.norm();
    if (!(range > 0) || !(range <= params.max_depth_m)) continue;  // also drops NaN
    SurfacePoint q;
    q.x = p.x(), q.y = p.y(), q.z = p.z();
    q.r = q.g = q.b = 0;
    q.a = 255;
    raw->push_back(q);
  }
  return surfaceOf(raw, params);
}

SurfaceCloud makeSurfaceCloud(const RgbdImage& view, const SurfaceParams& params) {
  validate(view);
  validate(params);
  pcl::PointCloud<SurfacePoint>::Ptr raw(new pcl::PointCloud<SurfacePoint>);
  const auto& K = view.intrinsics;
  raw->reserve(static_cast<std::size_t>(view.depth_m.total()));
  for (int v = 0; v < view.depth_m.rows; ++v) {
    const float* d = view.depth_m.ptr<float>(v);
    const cv::Vec3b* c = view.bgr.empty() ? nullptr : view.bgr.ptr<cv::Vec3b>(v);
    for (int u = 0; u < view.depth_m.cols; ++u) {
      const float z = d[u];
      if (!(z > 0) || !(z <= params.max_depth_m)) continue;  // also drops NaN
      const Eigen::Vector3d p = K.unproject(u, v, z);
      SurfacePoint q;
      q.x = static_cast<float>(p.x());
      q.y = static_cast<float>(p.y());
      q.z = static_cast<float>(p.z());
      if (c) {
        q.b = c[u][0];
        q.g = c[u][1];
        q.r = c[u][2];
      } else {
        q.r = q.g = q.b = 0;
      }
      q.a = 255;
      raw->push_back(q);
    }
  }
  return surfaceOf(raw, params);
}

int nearestWithNormal(const SurfaceCloud& surface, const Eigen::Vector3f& p, double max_distance_m) {
  if (surface.points->empty()) return -1;
  SurfacePoint q;
  q.x = p.x();
  q.y = p.y();
  q.z = p.z();
  pcl::Indices idx;
  std::vector<float> d2;
  if (surface.tree->nearestKSearch(q, 1, idx, d2) < 1) return -1;
  if (d2[0] > max_distance_m * max_distance_m) return -1;
  const auto& n = (*surface.normals)[static_cast<std::size_t>(idx[0])];
  if (!std::isfinite(n.normal_x) || !std::isfinite(n.normal_y) || !std::isfinite(n.normal_z)) return -1;
  return idx[0];
}

}  // namespace gasp::baselines
