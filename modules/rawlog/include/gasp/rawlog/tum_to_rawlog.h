#pragma once
/// \file tum_to_rawlog.h Converts a TUM RGB-D folder into an MRPT rawlog (+ ground truth file).
#include <cstddef>
#include <optional>
#include <string>

#include "gasp/core/tum_dataset.h"
#include "gasp/rawlog/rawlog_writer.h"
#include "gasp/rawlog/rgbd_frame.h"

namespace gasp {

struct TumToRawlogOptions {
  /// Depth (and rgb) intrinsics; when unset, TumDataset's choice (DIR/intrinsics.txt, a preset
  /// guessed from the folder name, else ROS default).
  std::optional<CameraIntrinsics> intrinsics;
  RawlogWriterOptions writer;          ///< format, external storage, compression
  bool with_rgb = true;                ///< store the associated rgb image when there is one
  /// TumDataset::Options::undistort: images resampled to the pinhole camera, whose intrinsics
  /// (no distortion) the observations then carry.
  bool undistort = true;
  std::size_t max_frames = 0;          ///< 0 = all depth frames
  std::string sensor_label = "RGBD";   ///< sensorLabel of the observations
};

struct TumToRawlogSummary {
  std::size_t frames_written = 0;
  std::size_t frames_with_rgb = 0;
  std::size_t frames_with_ground_truth = 0;
  std::string rawlog_path;
  std::string ground_truth_path;  ///< empty when no frame had ground truth (no file written)
  std::string images_directory;   ///< empty unless external storage was used
  std::string intrinsics_source;  ///< where the intrinsics came from
  CameraIntrinsics intrinsics;
};

/// OUT.rawlog -> OUT_groundtruth.txt (same folder; the last extension is replaced).
std::string groundTruthPathForRawlog(const std::string& rawlog_path);

/// Frame i of a TUM folder: raw uint16 depth kept (units per metre from the dataset, 5000 for
/// TUM), depth in metres, the dataset's intrinsics for depth and rgb (TUM depth is registered to
/// rgb: T_depth_rgb = identity), the associated rgb when with_rgb and present, and
/// T_robot_camera = mrptCameraFromOptical() (camera looking along the robot's +X, so MRPT's
/// sensorPose is the identity).
RgbdFrame frameFromTum(const TumDataset& dataset, std::size_t i, bool with_rgb = true,
                       const std::string& sensor_label = "RGBD");

/// Writes the depth frames of TUM_DIR as CObservation3DRangeScan into out_rawlog and the ground
/// truth of the frames that have one (timestamps = depth timestamps, optical camera poses as in
/// groundtruth.txt) as a TUM trajectory at groundTruthPathForRawlog(out_rawlog). Throws
/// gasp::Error (missing folder, unreadable images, unwritable output).
TumToRawlogSummary convertTumToRawlog(const std::string& tum_dir, const std::string& out_rawlog,
                                      const TumToRawlogOptions& options = {});

}  // namespace gasp
