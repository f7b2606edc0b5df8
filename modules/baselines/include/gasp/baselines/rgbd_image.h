#pragma once
/// \file rgbd_image.h One view as the feature baselines see it: depth, optional colour, intrinsics.
#include <opencv2/core.hpp>

#include "gasp/core/camera_intrinsics.h"

namespace gasp::baselines {

struct RgbdImage {
  cv::Mat depth_m;  ///< CV_32FC1 [m], 0 or NaN = no data
  /// CV_8UC3 BGR registered to the depth image (same size, pixel (u, v) sees the same point, as in
  /// TUM RGB-D); empty when the view has no colour (then only FPFH and SHOT apply).
  cv::Mat bgr;
  CameraIntrinsics intrinsics;  ///< of the depth image (and of bgr)
};

/// Throws gasp::Error unless depth_m is CV_32FC1 of the intrinsics' size and bgr is empty or
/// CV_8UC3 of the same size.
void validate(const RgbdImage& view);

}  // namespace gasp::baselines
