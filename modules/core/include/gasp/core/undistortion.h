#pragma once
/// \file undistortion.h Depth (and colour) images resampled from a camera with lens distortion to
/// the ideal pinhole camera with the same fx, fy, cx, cy, so that every later stage can use the
/// pinhole model (CameraIntrinsics::unproject / project).
///
/// Depth is resampled by nearest neighbour: interpolating depth would invent points between a
/// foreground and a background surface at every depth edge. Colour is resampled bilinearly.
///
/// Why: the TUM freiburg1 depth images are registered to the colour camera, whose calibration has
/// strong radial distortion (k1 0.26, k2 -0.95, k3 1.16). Measured on fr1_xyz (docs/pipeline.md,
/// "Lens distortion"), undistorting with these coefficients lowers the pair benchmark's
/// translation RMSE by 13-20 % and its rotation RMSE by up to 7 %; applying them with the opposite
/// sign makes both worse, so the depth images do carry that distortion.
#include <opencv2/core.hpp>

#include <memory>
#include <utility>

#include "gasp/core/camera_intrinsics.h"

namespace gasp {

/// True when any distortion coefficient of k is non-zero.
bool hasLensDistortion(const CameraIntrinsics& k);

class Undistortion {
 public:
  /// Builds the resampling maps for k (k.validate() must hold). With no distortion the maps are
  /// not built and apply*() return their input.
  explicit Undistortion(const CameraIntrinsics& k);

  /// The intrinsics of the resampled images: k with the distortion coefficients set to zero.
  const CameraIntrinsics& pinhole() const { return pinhole_; }
  bool active() const { return !map_x_.empty(); }

  /// Depth, CV_16UC1 (raw units) or CV_32FC1 (metres), of the size of k; nearest neighbour, pixels
  /// that map outside the image (or onto missing depth) are 0. Throws gasp::Error for another type
  /// or size.
  cv::Mat applyToDepth(const cv::Mat& depth) const;
  /// An 8-bit colour or grey image of the size of k (bilinear, black outside). An empty input
  /// gives an empty output. Throws gasp::Error for another size.
  cv::Mat applyToImage(const cv::Mat& image) const;

 private:
  CameraIntrinsics pinhole_;
  cv::Mat map_x_, map_y_;  ///< CV_32FC1: the distorted pixel each pinhole pixel samples
};

/// An Undistortion for k from a small process-wide cache (the last few intrinsics used; building
/// the maps of a 640x480 camera takes milliseconds, applying them 0.3 ms). Thread-safe.
std::shared_ptr<const Undistortion> sharedUndistortion(const CameraIntrinsics& k);

/// `depth` resampled to the pinhole camera (sharedUndistortion(k)->applyToDepth) with the pinhole
/// intrinsics when k has lens distortion; both as given otherwise.
std::pair<cv::Mat, CameraIntrinsics> pinholeDepth(const cv::Mat& depth, const CameraIntrinsics& k);

}  // namespace gasp
