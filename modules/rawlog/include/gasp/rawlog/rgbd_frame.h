#pragma once
/// \file rgbd_frame.h One RGB-D frame as GASP sees it: depth [m], raw depth, rgb, intrinsics and
/// the camera's poses. MRPT-free; observation_conversion.h converts to and from MRPT.
#include <opencv2/core.hpp>

#include <optional>
#include <string>

#include "gasp/core/camera_intrinsics.h"
#include "gasp/core/pose.h"
#include "gasp/core/range_scan.h"

namespace gasp {

/// A depth image with its optional rgb image. All camera frames are optical (x right, y down,
/// z forward), as everywhere in GASP. Or a rotating LiDAR's sweep (`sweep` set, no images): its
/// frame is MRPT's LiDAR frame (x ahead, z up).
struct RgbdFrame {
  double timestamp = 0.0;  ///< acquisition time [s] (UNIX epoch for TUM data)

  cv::Mat depth_m;  ///< depth along the optical axis [m], CV_32FC1; 0 = no data
  /// The depth as stored (CV_16UC1, 0 = no data) when it is integer depth; empty otherwise (e.g.
  /// for MRPT scans with range_is_depth = false, which are converted to depth in metres).
  cv::Mat depth_raw;
  double depth_units_per_metre = 0.0;  ///< scale of depth_raw (5000 for TUM); 0 when no raw
  CameraIntrinsics depth_intrinsics;   ///< pinhole model of the depth camera

  cv::Mat rgb;  ///< CV_8UC3 BGR colour (or the intensity image made BGR); may be empty
  CameraIntrinsics rgb_intrinsics;  ///< model of the rgb camera (meaningful when rgb is set)

  /// Pose of the rgb camera in the depth camera (p_depth = T_depth_rgb * p_rgb); identity when
  /// they coincide (TUM registered depth).
  Isometry3 T_depth_rgb = Isometry3::Identity();
  /// Pose of the depth camera's optical frame on the robot (MRPT's sensorPose, re-expressed for
  /// the optical frame): p_robot = T_robot_camera * p_camera. For a sweep: the LiDAR's sensorPose
  /// as it is (p_robot = T_robot_camera * p_lidar).
  Isometry3 T_robot_camera = Isometry3::Identity();

  std::string sensor_label = "RGBD";  ///< MRPT sensorLabel

  /// A rotating LiDAR's sweep (range_scan.h's rangeScanFrom()) instead of a depth image.
  std::optional<RangeScan> sweep;

  bool hasRgb() const { return !rgb.empty(); }
  bool isSweep() const { return sweep.has_value(); }
  bool hasRawDepth() const { return !depth_raw.empty() && depth_units_per_metre > 0.0; }
};

}  // namespace gasp
