#pragma once
/// \file tum_dataset.h Reader for a TUM RGB-D folder (depth.txt, rgb.txt, groundtruth.txt).
#include <opencv2/core.hpp>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "gasp/core/camera_intrinsics.h"
#include "gasp/core/depth_image.h"
#include "gasp/core/tum_trajectory.h"
#include "gasp/core/undistortion.h"

namespace gasp {

/// One depth frame of a TUM folder, in depth.txt order.
struct TumFrame {
  double timestamp = 0.0;                 ///< depth timestamp [s]
  std::string depth_path;                 ///< absolute or folder-relative path of the depth PNG
  std::optional<double> rgb_timestamp;    ///< associated rgb frame (associate.py, |dt| < max_dt)
  std::optional<std::string> rgb_path;
  std::optional<Isometry3> T_world_camera;  ///< ground truth, nearest in time within max_dt
};

/// A `timestamp filename` list (depth.txt, rgb.txt) in strictly increasing time order; '#' lines
/// skipped; errors (malformed lines, a repeated or earlier timestamp) name file:line.
std::vector<std::pair<double, std::string>> readTumFileList(const std::string& path);

class TumDataset {
 public:
  struct Options {
    /// Intrinsics to use; when unset: DIR/intrinsics.txt if present (GASP's simulator writes
    /// it), else a TUM preset guessed from the folder name (freiburg1/fr1_, ...), else ROS default.
    std::optional<CameraIntrinsics> intrinsics;
    double max_dt = 0.02;  ///< rgb and ground-truth association tolerance [s] (TUM: 0.02)
    double depth_units_per_metre = kTumDepthUnitsPerMetre;
    /// Resample depth and rgb to the pinhole camera when the intrinsics carry lens distortion
    /// (the fr1 and fr2 presets do; undistortion.h says why). Off: images as stored, and the
    /// distortion is ignored.
    bool undistort = true;
  };

  /// Opens DIR: depth.txt is required, rgb.txt and groundtruth.txt optional. Throws gasp::Error
  /// for a missing folder or depth.txt and for malformed lines (with file and line).
  static TumDataset open(const std::string& dir, const Options& options);
  static TumDataset open(const std::string& dir) { return open(dir, Options{}); }

  const std::string& directory() const { return dir_; }
  /// The intrinsics of the images load*() returns: pinhole (no distortion) when undistorting.
  const CameraIntrinsics& intrinsics() const { return undistortion_->pinhole(); }
  /// The intrinsics as chosen (option, file or preset), with their distortion coefficients.
  const CameraIntrinsics& calibratedIntrinsics() const { return intrinsics_; }
  /// True when load*() resample the images (Options::undistort and the intrinsics have distortion).
  bool undistorts() const { return undistortion_->active(); }
  /// Where the intrinsics came from: "option", "DIR/intrinsics.txt", "preset fr1 (folder name)"...
  const std::string& intrinsicsSource() const { return intrinsics_source_; }
  /// True when no intrinsics were given, found in DIR/intrinsics.txt or guessed from the folder
  /// name: the ROS default (fx = fy = 525) is then assumed, which a user's own camera seldom has.
  bool intrinsicsAreTheDefaultGuess() const { return intrinsics_guessed_; }
  /// One line for the programs' output: "fx 517.3 fy 516.5 cx 318.6 cy 255.3 (640x480, SOURCE)",
  /// the calibrated intrinsics (with ", undistorted" when the images are resampled).
  std::string intrinsicsSummary() const;
  /// "" or, when intrinsicsAreTheDefaultGuess(), a warning saying so and how to give the camera's.
  std::string intrinsicsWarning() const;
  double depthUnitsPerMetre() const { return options_.depth_units_per_metre; }

  std::size_t size() const { return frames_.size(); }
  const TumFrame& frame(std::size_t i) const;
  const std::vector<TumFrame>& frames() const { return frames_; }
  /// The whole groundtruth.txt (empty when absent).
  const Trajectory& groundTruth() const { return ground_truth_; }
  /// Ground truth of frame i looked up at its depth timestamp + offset_s (nearest within
  /// Options::max_dt); offset 0 gives frame(i).T_world_camera. TUM fr1's depth lags its motion
  /// capture (docs/pipeline.md): a negative offset fits it better.
  std::optional<Isometry3> groundTruthOf(std::size_t i, double offset_s = 0.0) const;
  /// Ground truth at time t [s]: the pose nearest in time, within Options::max_dt.
  std::optional<Isometry3> groundTruthAt(double t) const;
  /// Number of depth frames that have a ground-truth pose.
  std::size_t countWithGroundTruth() const;

  cv::Mat loadDepthRaw(std::size_t i) const;  ///< uint16 units as stored (undistorted); size checked
  cv::Mat loadDepth(std::size_t i) const;     ///< metres, CV_32FC1 (undistorted)
  cv::Mat loadRgb(std::size_t i) const;       ///< BGR 8-bit (undistorted); empty when the frame has no rgb

 private:
  TumDataset() = default;  // open() builds one
  std::string dir_;
  Options options_;
  CameraIntrinsics intrinsics_;
  std::string intrinsics_source_;
  bool intrinsics_guessed_ = false;
  std::shared_ptr<const Undistortion> undistortion_;  ///< shared by copies (immutable maps)
  std::vector<TumFrame> frames_;
  Trajectory ground_truth_;
};

}  // namespace gasp
