#pragma once
/// \file camera_roll.h A depth (or colour) image turned by a quarter turn, and the camera that
/// would have taken it: the same camera rolled about its optical axis. Used to test invariance to
/// camera roll on real data (gasp-pairs --roll-target): turning an image by 180 deg is exactly what
/// a camera rolled by 180 deg sees, with no resampling.
#include <opencv2/core.hpp>

#include "gasp/core/camera_intrinsics.h"
#include "gasp/core/pose.h"

namespace gasp {

/// Throws gasp::Error unless clockwise_deg is 0, 90, 180 or 270.
void requireQuarterTurn(int clockwise_deg);

/// The image turned clockwise by clockwise_deg as it is displayed (cv::rotate; 90 and 270 swap
/// width and height). Pixel (u, v) of a W x H image goes to (H-1-v, u) at 90, (W-1-u, H-1-v) at
/// 180 and (v, W-1-u) at 270.
cv::Mat turnImage(const cv::Mat& image, int clockwise_deg);

/// The intrinsics of the turned image: the principal point moved with its pixel, fx and fy (and
/// width and height) swapped at 90 and 270. Throws gasp::Error for a lens with distortion unless
/// the turn is 0 (the images GASP reads are undistorted first, see undistortion.h).
CameraIntrinsics turnIntrinsics(const CameraIntrinsics& intrinsics, int clockwise_deg);

/// T_turned_camera: the rotation about the optical axis taking points of the camera to the
/// camera of the turned image (p_turned = T * p), so that intrinsics.unproject of pixel (u, v)
/// mapped by T equals turnIntrinsics(...).unproject of the turned pixel. (-x, -y, z) at 180 deg.
Isometry3 turnRotation(int clockwise_deg);

}  // namespace gasp
