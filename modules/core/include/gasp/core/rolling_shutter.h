#pragma once
/// \file rolling_shutter.h Depth images from a rolling-shutter sensor carried to one instant.
///
/// A rolling-shutter camera exposes its rows one after the other. While the camera moves, row r
/// sees the scene from the pose at time t(r) = t_stamp + (r / (H - 1) - 1/2) * readout_s, so a
/// moving camera's depth image is a sheared, stretched copy of the scene. deskewDepth() resamples
/// the image to the camera pose at the stamp, given the camera's velocity (a constant twist over
/// the readout):
///   p(t_stamp) = exp([w dt]) p(t(r)) + v dt,   dt = t(r) - t_stamp        (first order in dt)
/// with p in the camera frame, v [m/s] and w [rad/s] the camera's velocity in its own frame.
///
/// The target pixel's source position is found by fixed-point iteration of the (depth-dependent)
/// warp, which is close to the identity. Depth there is interpolated bilinearly when the four
/// neighbouring pixels lie within 3 % of each other (one surface), else taken from the nearest
/// pixel, so that no point is invented between a foreground and a background surface (as in
/// undistortion.h). A target pixel without depth of its own starts from a neighbour's shift, so
/// holes move with the image and do not grow. Pixels whose iteration does not converge get no
/// depth. There is no depth test: where the warp folds at a depth edge (a foreground edge moving
/// over the background), a target pixel may take the background point the foreground hides; such
/// folds are as wide as the shift, a pixel or two at hand-held speeds.
///
/// Why: consumer depth cameras (Kinect, Xtion) read their rows out over most of the frame time
/// (Kerl, Stueckler, Cremers, "Dense continuous-time tracking and mapping with rolling shutter
/// RGB-D cameras", ICCV 2015). On TUM fr1_xyz a readout of 30 ms, with the velocity from each
/// frame's neighbours, lowers the pair benchmark's rotation RMSE at skips 30-100 by 13-27 %
/// (docs/pipeline.md, "Rolling shutter").
#include <opencv2/core.hpp>

#include <Eigen/Core>

#include "gasp/core/camera_intrinsics.h"
#include "gasp/core/pose.h"

namespace gasp {

/// The camera's velocity in its own (optical) frame.
struct CameraTwist {
  Eigen::Vector3d v_mps = Eigen::Vector3d::Zero();    ///< linear velocity [m/s]
  Eigen::Vector3d w_radps = Eigen::Vector3d::Zero();  ///< angular velocity [rad/s]
};

/// The twist that moves the camera from T_world_a to T_world_b in dt_s seconds (constant
/// velocity), expressed in camera a's frame (the frame at the middle of the motion differs by
/// half the motion's rotation: second order for the deskew).
/// Throws gasp::Error when dt_s is not positive and finite.
CameraTwist twistBetween(const Isometry3& T_world_a, const Isometry3& T_world_b, double dt_s);

/// The pose at dt_s relative to the pose at 0 of a sensor moving at the constant twist `twist`
/// (in its own frame): rotation exp([w dt]), translation v dt (first order in the translation, as
/// twistBetween()).
Isometry3 twistMotion(const CameraTwist& twist, double dt_s);

/// The depth image (CV_32FC1, metres; 0 or NaN = no depth) resampled to the camera pose at the
/// image's stamp (the middle row); pixels without a source are 0. readout_s is the time from the first row to the
/// last; negative when the sensor reads bottom-up; 0 returns a copy. Throws gasp::Error for
/// another image type, a size that is not the intrinsics', or a non-finite twist or readout.
cv::Mat deskewDepth(const cv::Mat& depth, const CameraIntrinsics& k, const CameraTwist& twist,
                    double readout_s);

}  // namespace gasp
