#pragma once
/// \file segmentation_picture.h A picture of a decomposition a person can read: each patch in its
/// own colour over shaded depth, patch borders darker, valid pixels in no patch grey, no depth black.
#include <opencv2/core.hpp>

#include "gasp/superpixels/surface_patch.h"

namespace gasp {

/// A distinct, deterministic BGR colour per patch id.
cv::Vec3b patchColour(int id);

/// BGR 8-bit picture of `seg` over the depth image [m] it came from.
cv::Mat drawSegmentation(const cv::Mat& depth_m, const SuperpixelSegmentation& seg);

}  // namespace gasp
