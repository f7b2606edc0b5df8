#include "gasp/sim/renderer.h"

#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "gasp/core/error.h"

namespace gasp::sim {

namespace {

/// An object prepared for one view: the camera-to-object transform and its bounding sphere.
struct PreparedObject {
  const SceneObject* object = nullptr;
  Eigen::Matrix3d R_object_camera;
  Eigen::Vector3d t_object_camera;      ///< camera centre in the object frame
  Eigen::Matrix3d R_camera_object;
  Eigen::Vector3d centre_camera;        ///< bounding sphere centre in the camera frame
  double radius_sq = 0.0;               ///< bounding radius squared (inf: always tested)
  bool always = false;
};

/// The objects visible at frame_index, prepared for rays from the sensor pose T_world_sensor.
std::vector<PreparedObject> prepareObjects(const Scene& scene, const Isometry3& T_world_sensor, int frame_index) {
  const Isometry3 T_sensor_world = T_world_sensor.inverse();
  std::vector<PreparedObject> prepared;
  for (const auto& obj : scene.objects) {
    if (!obj.visibleAt(frame_index)) continue;
    PreparedObject p;
    p.object = &obj;
    const Isometry3 T_object_sensor = obj.T_world_object.inverse() * T_world_sensor;
    p.R_object_camera = T_object_sensor.linear();
    p.t_object_camera = T_object_sensor.translation();
    p.R_camera_object = p.R_object_camera.transpose();
    p.centre_camera = T_sensor_world * obj.T_world_object.translation();
    const double r = boundingRadius(obj.shape);
    p.always = !std::isfinite(r);
    p.radius_sq = r * r;
    prepared.push_back(p);
  }
  return prepared;
}

/// The nearest hit along the ray t * d (sensor frame, from its origin; t in units of |d|):
/// its t, the hit and its object; false when the ray hits nothing.
bool nearestHit(const std::vector<PreparedObject>& prepared, const Eigen::Vector3d& d, double& best_t, RayHit& best_hit,
                const PreparedObject*& best_obj) {
  constexpr double kTMin = 1e-6;
  const double dd = d.squaredNorm();
  best_t = std::numeric_limits<double>::infinity();
  best_obj = nullptr;
  for (const auto& p : prepared) {
    if (!p.always) {  // bounding-sphere early out
      const double q = p.centre_camera.dot(d);
      const double disc = q * q - dd * (p.centre_camera.squaredNorm() - p.radius_sq);
      if (disc < 0.0) continue;
      if ((q - std::sqrt(disc)) / dd >= best_t) continue;
    }
    RayHit hit;
    if (intersect(p.object->shape, p.t_object_camera, p.R_object_camera * d, kTMin, hit) && hit.t < best_t) {
      best_t = hit.t;
      best_hit = hit;
      best_obj = &p;
    }
  }
  return best_obj != nullptr;
}

/// Casts the rows [row_begin, row_end) of `out` (allocated) from the camera pose T_world_camera.
void renderRows(const Scene& scene, const CameraIntrinsics& K, const Isometry3& T_world_camera, int frame_index,
                int row_begin, int row_end, RenderedFrame& out) {
  const std::vector<PreparedObject> prepared = prepareObjects(scene, T_world_camera, frame_index);
  for (int v = row_begin; v < row_end; ++v) {
    auto* depth_row = out.depth.ptr<float>(v);
    auto* id_row = out.surface_id.ptr<std::uint16_t>(v);
    auto* normal_row = out.normal.ptr<cv::Vec3f>(v);
    for (int u = 0; u < K.width; ++u) {
      const Eigen::Vector3d d_camera((u - K.cx) / K.fx, (v - K.cy) / K.fy, 1.0);
      double best_t = 0.0;
      RayHit best_hit;
      const PreparedObject* best_obj = nullptr;
      if (!nearestHit(prepared, d_camera, best_t, best_hit, best_obj)) continue;
      Eigen::Vector3d n = best_obj->R_camera_object * best_hit.normal;
      if (n.dot(d_camera) > 0.0) n = -n;  // face the camera (rectangles are two-sided)
      depth_row[u] = static_cast<float>(best_t);
      id_row[u] = best_obj->object->surfaceId(best_hit.face);
      normal_row[u] = cv::Vec3f(static_cast<float>(n.x()), static_cast<float>(n.y()),
                                static_cast<float>(n.z()));
    }
  }
}

RenderedFrame emptyFrame(const CameraIntrinsics& K) {
  RenderedFrame out;
  out.depth = cv::Mat::zeros(K.height, K.width, CV_32FC1);
  out.surface_id = cv::Mat::zeros(K.height, K.width, CV_16UC1);
  out.normal = cv::Mat::zeros(K.height, K.width, CV_32FC3);
  return out;
}

}  // namespace

namespace {

RenderedScan emptyScan(const RangeScan& layout, const char* who) {
  const int rows = static_cast<int>(layout.elevation_rad.size()), cols = static_cast<int>(layout.azimuth_rad.size());
  if (rows == 0 || cols == 0) throw Error(std::string(who) + ": the layout has no rows or no columns");
  RenderedScan out;
  out.range = cv::Mat::zeros(rows, cols, CV_32FC1);
  out.surface_id = cv::Mat::zeros(rows, cols, CV_16UC1);
  return out;
}

/// Casts the columns [col_begin, col_end) of `out` (allocated) from the sensor pose T_world_sensor.
void renderColumns(const Scene& scene, const RangeScan& layout, const Isometry3& T_world_sensor, int frame_index,
                   int col_begin, int col_end, RenderedScan& out) {
  const std::vector<PreparedObject> prepared = prepareObjects(scene, T_world_sensor, frame_index);
  for (int r = 0; r < out.range.rows; ++r)
    for (int c = col_begin; c < col_end; ++c) {
      const Eigen::Vector3d d = layout.direction(r, c);  // unit: t is the range
      double t = 0.0;
      RayHit hit;
      const PreparedObject* obj = nullptr;
      if (!nearestHit(prepared, d, t, hit, obj)) continue;
      out.range.at<float>(r, c) = static_cast<float>(t);
      out.surface_id.at<std::uint16_t>(r, c) = obj->object->surfaceId(hit.face);
    }
}

}  // namespace

RenderedScan renderRangeScan(const Scene& scene, const RangeScan& layout, const Isometry3& T_world_sensor,
                             int frame_index) {
  RenderedScan out = emptyScan(layout, "renderRangeScan");
  renderColumns(scene, layout, T_world_sensor, frame_index, 0, out.range.cols, out);
  return out;
}

RenderedScan renderMovingRangeScan(const Scene& scene, const RangeScan& layout,
                                   const std::function<Isometry3(int)>& T_world_sensor_of_column, int frame_index) {
  if (!T_world_sensor_of_column) throw Error("renderMovingRangeScan: no pose function");
  RenderedScan out = emptyScan(layout, "renderMovingRangeScan");
  for (int c = 0; c < out.range.cols; ++c)
    renderColumns(scene, layout, T_world_sensor_of_column(c), frame_index, c, c + 1, out);
  return out;
}

RenderedFrame renderFrame(const Scene& scene, const CameraIntrinsics& K,
                          const Isometry3& T_world_camera, int frame_index) {
  K.validate();
  RenderedFrame out = emptyFrame(K);
  renderRows(scene, K, T_world_camera, frame_index, 0, K.height, out);
  return out;
}

RenderedFrame renderRollingShutterFrame(const Scene& scene, const CameraIntrinsics& K,
                                        const std::function<Isometry3(int)>& T_world_camera_of_row,
                                        int frame_index) {
  K.validate();
  if (!T_world_camera_of_row) throw Error("renderRollingShutterFrame: no pose function");
  RenderedFrame out = emptyFrame(K);
  for (int v = 0; v < K.height; ++v) renderRows(scene, K, T_world_camera_of_row(v), frame_index, v, v + 1, out);
  return out;
}

}  // namespace gasp::sim
