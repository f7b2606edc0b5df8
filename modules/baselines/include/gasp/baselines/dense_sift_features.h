#pragma once
/// \file dense_sift_features.h The paper's dense SIFT baseline: SIFT descriptors (cv::SIFT::compute,
/// no detection) on a regular pixel grid, step step_px (the paper: 8), at each scale s of `scales`
/// (the paper: 1, 3, 9), upright (orientation 0, as VLFeat's dense SIFT). Scale s is the SIFT
/// sigma in pixels: OpenCV's KeyPoint::size = 2 s, so a descriptor's spatial bin is 3 s px wide and
/// its window 4 x 3 s = 12, 36, 108 px for the paper's scales. Each (grid point, scale) is one
/// keypoint; grid points without depth or without a normal are dropped (as for SIFT).
#include <vector>

#include "gasp/baselines/described_keypoints.h"
#include "gasp/baselines/rgbd_image.h"
#include "gasp/baselines/surface_params.h"

namespace gasp::baselines {

struct DenseSiftParams {
  SurfaceParams surface;                ///< where the keypoints' normals come from
  int step_px = 8;                      ///< grid step [px]; the first point is at (step/2, step/2)
  std::vector<double> scales{1, 3, 9};  ///< SIFT sigma per scale [px]
};

/// Throws gasp::Error naming the first invalid parameter.
void validate(const DenseSiftParams& params);

/// Throws gasp::Error for an invalid view or a view without colour.
DescribedKeypoints describeDenseSift(const RgbdImage& view, const DenseSiftParams& params = {});

}  // namespace gasp::baselines
