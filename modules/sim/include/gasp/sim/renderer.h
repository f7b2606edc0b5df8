#pragma once
/// \file renderer.h Analytic ray casting of a scene into a pinhole depth camera.
#include <opencv2/core.hpp>

#include <functional>

#include "gasp/core/camera_intrinsics.h"
#include "gasp/core/pose.h"
#include "gasp/core/range_scan.h"
#include "gasp/sim/scene.h"

namespace gasp::sim {

/// Ground truth of one view: for each pixel the nearest surface along the pixel's ray.
struct RenderedFrame {
  cv::Mat depth;       ///< CV_32FC1 true depth z [m] (optical frame); 0 where the ray hits nothing
  cv::Mat surface_id;  ///< CV_16UC1 surface id of the hit; 0 where the ray hits nothing
  /// CV_32FC3 unit surface normal (x, y, z) in the camera frame, turned to face the camera;
  /// zero where the ray hits nothing.
  cv::Mat normal;
};

/// Casts one ray per pixel centre (u, v) through the pinhole (no distortion) and keeps the
/// nearest hit of the objects visible at frame_index. Exact up to double rounding; the depth is
/// stored as float.
RenderedFrame renderFrame(const Scene& scene, const CameraIntrinsics& intrinsics,
                          const Isometry3& T_world_camera, int frame_index = 0);

/// A rolling-shutter view: row v is cast from the pose T_world_camera_of_row(v) (depth and
/// normals in that row's camera frame), as a sensor that exposes its rows one after the other
/// sees a scene while it moves (gasp/core/rolling_shutter.h). The scene is prepared again for
/// every row, so it is slower than renderFrame (tests use it). Throws gasp::Error for an empty
/// function.
RenderedFrame renderRollingShutterFrame(const Scene& scene, const CameraIntrinsics& intrinsics,
                                        const std::function<Isometry3(int)>& T_world_camera_of_row,
                                        int frame_index = 0);

/// Ground truth of a LiDAR sweep: for each cell the nearest surface along its ray.
struct RenderedScan {
  cv::Mat range;       ///< CV_32FC1 true range [m]; 0 where the ray hits nothing
  cv::Mat surface_id;  ///< CV_16UC1 surface id of the hit; 0 where the ray hits nothing
};

/// Casts the ray of every cell of `layout` (its elevations and azimuths, RangeScan::direction();
/// its ranges are not used) from the sensor pose T_world_sensor, the whole sweep from that one
/// pose. Throws gasp::Error for a layout without rows or columns.
RenderedScan renderRangeScan(const Scene& scene, const RangeScan& layout, const Isometry3& T_world_sensor,
                             int frame_index = 0);

/// A sweep taken while the sensor moves: column c is cast from the pose T_world_sensor_of_column(c)
/// (ranges along that column's rays from that pose), as a spinning sensor fires its columns one
/// after the other (RangeScan: columns in the order the sweep took them). The scene is prepared
/// again for every column. Throws gasp::Error for an empty function or a layout without rows or
/// columns.
RenderedScan renderMovingRangeScan(const Scene& scene, const RangeScan& layout,
                                   const std::function<Isometry3(int)>& T_world_sensor_of_column,
                                   int frame_index = 0);

}  // namespace gasp::sim
