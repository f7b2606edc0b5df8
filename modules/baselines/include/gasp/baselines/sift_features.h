#pragma once
/// \file sift_features.h The paper's SIFT baseline: OpenCV's SIFT (Lowe 2004; cv::SIFT, OpenCV's
/// default parameters) detected and described on the grey rgb image, keypoints back-projected to
/// 3D with the depth at their (rounded) pixel; keypoints without depth, or without a surface normal
/// within surface.voxel_m * 2 of their 3D point (surface_params.h), are dropped.
#include "gasp/baselines/described_keypoints.h"
#include "gasp/baselines/rgbd_image.h"
#include "gasp/baselines/surface_params.h"

namespace gasp::baselines {

struct SiftParams {
  SurfaceParams surface;            ///< where the keypoints' normals come from
  int max_features = 0;             ///< cv::SIFT nfeatures (0 = all)
  double contrast_threshold = 0.04; ///< cv::SIFT contrastThreshold (OpenCV's default)
};

/// Throws gasp::Error naming the first invalid parameter.
void validate(const SiftParams& params);

/// Throws gasp::Error for an invalid view or a view without colour.
DescribedKeypoints describeSift(const RgbdImage& view, const SiftParams& params = {});

}  // namespace gasp::baselines
