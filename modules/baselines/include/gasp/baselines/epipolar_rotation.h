#pragma once
/// \file epipolar_rotation.h A depth-free check of a relative rotation: SIFT matches between the
/// two colour images (Lowe's ratio test and the mutual check, descriptor_matching.h), the essential
/// matrix by OpenCV's five-point solver (Nister 2004) inside RANSAC, and its decomposition
/// (cv::recoverPose, the cheirality test picks R and the translation direction).
///
/// Why it exists: `gasp-pairs --polish-reference` judges TUM's reference poses with GICP, which
/// reads the same depth images as GASP, so a bend in the Kinect's depth would mislead both alike.
/// The rotation between two images of a calibrated camera follows from the pixels alone (Hartley
/// and Zisserman, 9.6): no depth, no GASP code. `gasp-pairs --rgb-rotation-check` compares it
/// with the reference's rotation and with GASP's (docs/pipeline.md, "A depth-free check").
#include <Eigen/Core>
#include <opencv2/core.hpp>

#include <cstddef>
#include <string>

#include "gasp/core/camera_intrinsics.h"

namespace gasp::baselines {

struct EpipolarParams {
  double contrast_threshold = 0.04;  ///< cv::SIFT contrastThreshold (OpenCV's default; lower finds more in flat images)
  double ratio = 0.8;           ///< Lowe's ratio test on the SIFT matches, in (0, 1]
  double threshold_px = 1.0;    ///< RANSAC inlier distance to the epipolar line [px]
  double confidence = 0.9999;   ///< RANSAC confidence, in (0, 1)
  int max_iterations = 10000;   ///< RANSAC iteration cap
  int min_inliers = 50;         ///< fewer inliers (after the cheirality test): no estimate
  /// Below this median parallax of the inliers [px] (displacement the rotation does not explain;
  /// also applied to the matches' plain displacement before RANSAC) the translation direction --
  /// and with it the split between rotation and translation -- is not determined: no estimate.
  double min_parallax_px = 2.0;
};

/// Throws gasp::Error naming the first invalid parameter.
void validate(const EpipolarParams& params);

struct EpipolarResult {
  bool success = false;
  /// Rotation of the source camera into the target camera (x_target = R x_source + t).
  Eigen::Matrix3d R_target_source = Eigen::Matrix3d::Identity();
  Eigen::Vector3d t_direction = Eigen::Vector3d::Zero();  ///< unit translation direction, target frame
  std::size_t keypoints_source = 0, keypoints_target = 0;
  std::size_t matches = 0;    ///< after the ratio test and the mutual check
  std::size_t inliers = 0;    ///< RANSAC inliers that pass the cheirality test
  /// Median distance [px] of the inliers from where the rotation alone takes them (the parallax
  /// of the translation); 0 when no rotation was estimated.
  double median_parallax_px = 0.0;
  std::string reason;         ///< why there is no estimate
};

/// Colour images CV_8UC3 BGR (or CV_8UC1 grey) of one pinhole camera with intrinsics k (no lens
/// distortion: pass undistorted images, as TumDataset::loadRgb gives). Throws gasp::Error for an
/// empty image, another type, or a size other than the intrinsics'. Too few features or inliers,
/// or too little parallax, give success = false with the reason.
EpipolarResult estimateEpipolarRotation(const cv::Mat& image_source, const cv::Mat& image_target,
                                        const CameraIntrinsics& k, const EpipolarParams& params = {});

}  // namespace gasp::baselines
