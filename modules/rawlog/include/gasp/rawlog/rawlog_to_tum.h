#pragma once
/// \file rawlog_to_tum.h Converts the CObservation3DRangeScan of an MRPT rawlog into a TUM RGB-D
/// folder, so that every TUM tool (gasp-pairs, gasp-segment, gasp-associate --tum, TUM's own
/// scripts) runs on a robot's rawlog. The inverse of tum_to_rawlog.h.
///
/// Written: depth/<t>.png (uint16, 5000 units per metre, as TUM), depth.txt, intrinsics.txt (the
/// depth camera's, lens coefficients included: TumDataset then undistorts as for TUM's fr1),
/// rgb/<t>.png and rgb.txt when the colour image is registered to the depth (same intrinsics,
/// T_depth_rgb = identity, as TUM assumes), and groundtruth.txt copied from a given camera
/// trajectory. What TUM cannot hold is dropped and counted: the robot frame (sensorPose; the poses
/// are the camera's), colour images that are not registered to the depth, depth beyond 13.107 m
/// (uint16 at 5000 units per metre). The colour image is taken as colour whatever the scan's
/// intensityImageChannel says.
#include <cstddef>
#include <map>
#include <string>

#include "gasp/core/camera_intrinsics.h"

namespace gasp {

struct RawlogToTumOptions {
  /// Only the observations with this sensorLabel; empty: all, which must then share one label
  /// (and one depth camera).
  std::string sensor_label;
  /// A TUM trajectory of the camera (optical frame) poses, copied to groundtruth.txt; empty:
  /// none. gasp-tum2rawlog writes one beside its rawlog (OUT_groundtruth.txt).
  std::string ground_truth_path;
  bool with_rgb = true;         ///< write registered colour images
  std::size_t max_frames = 0;   ///< 0 = all
};

struct RawlogToTumSummary {
  std::size_t frames_written = 0;
  std::size_t frames_with_rgb = 0;
  std::size_t rgb_not_registered = 0;      ///< colour images left out: not registered to the depth
  std::size_t frames_other_sensor = 0;     ///< scans of another sensorLabel, skipped
  std::size_t pixels_beyond_range = 0;     ///< depth pixels beyond 13.107 m, written as 0 (no data)
  std::size_t frames_without_depth = 0;    ///< frames written with no depth pixel at all
  /// Scans whose sensorPose is not the identity: their robot frame is not kept (the folder's
  /// poses are the camera's).
  std::size_t sensor_pose_dropped = 0;
  std::map<std::string, std::size_t> other_objects;  ///< other rawlog objects, skipped
  std::string sensor_label;
  CameraIntrinsics intrinsics;             ///< the depth camera's, written to intrinsics.txt
  bool ground_truth = false;               ///< groundtruth.txt written
};

/// Writes the folder (created if missing; it must not already hold a depth.txt, rgb.txt,
/// groundtruth.txt or intrinsics.txt). On failure what this call wrote is removed again. Throws
/// gasp::Error: unreadable rawlog, no 3D range scan (of the label), several labels without
/// sensor_label, depth cameras that change within the sensor, two scans with the same timestamp
/// or out of time order, no scan with any depth to write, a file of the folder that exists
/// already, an unreadable trajectory, an unwritable folder.
RawlogToTumSummary convertRawlogToTum(const std::string& rawlog_path, const std::string& out_dir,
                                      const RawlogToTumOptions& options = {});

}  // namespace gasp
