#pragma once
/// \file smooth_components.h Smooth-surface components of a depth image (paper III-A, first step):
/// 4-connected regions whose neighbouring points are depth-connected with similar normals, built
/// from "core" pixels only (a normal exists and no crease); the rest is set aside.
#include <opencv2/core.hpp>

#include "gasp/superpixels/normals.h"

namespace gasp {

struct SmoothComponents {
  cv::Mat labels;  ///< CV_32S component id (0..count-1, raster order of first pixel); -1 set aside
  int count = 0;
};

SmoothComponents segmentSmoothComponents(const DepthLinks& links, const SurfaceNormals& normals,
                                         const SuperpixelParams& params);

/// Relabels a label image so that labels >= 0 become 0..n-1 in raster order of first appearance;
/// returns n.
int relabelInRasterOrder(cv::Mat& labels);

}  // namespace gasp
