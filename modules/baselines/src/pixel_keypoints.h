#pragma once
// Private: image keypoints (SIFT, dense SIFT) lifted to 3D with the depth and the surface normals.
#include <opencv2/core.hpp>

#include <vector>

#include "gasp/baselines/described_keypoints.h"
#include "gasp/baselines/rgbd_image.h"
#include "gasp/baselines/surface_params.h"

namespace gasp::baselines {

/// Keeps keypoint k (row k of descriptors) when the depth at its rounded pixel is valid (> 0,
/// <= max_depth_m) and a surface point with a finite normal lies within 2 voxels of its 3D point.
DescribedKeypoints liftPixelKeypoints(const RgbdImage& view, const std::vector<cv::KeyPoint>& keypoints,
                                      const cv::Mat& descriptors, const SurfaceParams& surface);

/// The grey image of a view's colour (throws gasp::Error when there is none; `who` names the method).
cv::Mat greyImage(const RgbdImage& view, const char* who);

}  // namespace gasp::baselines
