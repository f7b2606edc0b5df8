#pragma once
/// \file superpixel_map_view.h One observation inside a gasp::CSuperpixelMap: its depth view
/// (depth image, depth intrinsics, patches in the camera frame; or a LiDAR sweep's binned view
/// with its returns, in the LiDAR's frame), where its sensor was in the map, and the patches'
/// colours from the intensity image (when there was one).
#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "gasp/core/pose.h"
#include "gasp/pipeline/depth_view.h"
#include "gasp/pipeline/range_view.h"
#include "gasp/rawlog/rgbd_frame.h"

namespace gasp {

using Rgb8 = std::array<std::uint8_t, 3>;

struct SuperpixelMapView {
  DepthView view;                                   ///< camera frame (optical) of the depth camera
  Isometry3 T_map_camera = Isometry3::Identity();   ///< depth camera in the map
  /// Mean colour (R, G, B) of each patch's pixels seen by the intensity camera; empty for
  /// range-only observations. Patches outside the intensity image get the colour of their normal.
  std::vector<Rgb8> patch_rgb;
  double timestamp = 0.0;  ///< [s]
  std::string sensor_label;
};

/// A patch in the map frame.
struct MapPatch {
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();  ///< [m]
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();   ///< unit
  double area_m2 = 0.0;
  double radius_m = 0.0;
  Rgb8 rgb{};              ///< patch colour, or the colour of its normal
  int view = -1, patch = -1;  ///< where it comes from
};

/// Segments a frame (makeDepthView() with `params`; a LiDAR sweep: makeRangeView() with
/// lidarSuperpixelParams(lidar) and its returns, range_view.h) and places it in the map:
/// T_map_camera = T_map_robot * frame.T_robot_camera. Colours come from frame.rgb through the
/// intensity camera's own intrinsics and T_depth_rgb (a sweep has none: its patches take their
/// normals' colours). Throws gasp::Error for bad images, scans or parameters.
SuperpixelMapView makeMapView(const RgbdFrame& frame, const Isometry3& T_map_robot, const SuperpixelParams& params,
                              const LidarParams& lidar = {});

/// A colour for a patch without one: its normal in the camera frame mapped to RGB.
Rgb8 normalColour(const Eigen::Vector3d& normal);

/// The patches of a view in the map frame.
void appendMapPatches(const SuperpixelMapView& view, int view_index, std::vector<MapPatch>& out);

/// Checks the internal consistency of a view (sizes, label range, finite values, unit normals);
/// throws gasp::Error naming what is wrong. Used after deserialization.
void checkConsistency(const SuperpixelMapView& view);

}  // namespace gasp
