#pragma once
// The last step of the full-resolution labels (full_resolution.h): pixels no patch took.
#include <vector>

#include "gasp/core/view_projection.h"
#include "gasp/core/point_cloud.h"
#include "gasp/superpixels/depth_links.h"
#include "gasp/superpixels/superpixel_params.h"
#include "region_growing.h"

namespace gasp::detail {

/// Valid pixels still unlabelled (among `unlabelled`, every pixel that may be) form linked groups,
/// labelled from `count` on; those, and patches that came out below min_patch_pixels, join the
/// adjacent patch with the closest normal (smallest first), or stay on their own (a group of at
/// least min_patch_pixels) or are dropped as noise. models (one per label, pixel counts current)
/// gains the groups' models; merged labels stay unused.
void settleLeftoverPixels(int* L, int count, std::vector<PlaneModel>& models, const OrganizedPointCloud& cloud,
                          const DepthLinks& links, const PixelNormals& normals, const ViewProjection& k,
                          const SuperpixelParams& p, float min_cos, const std::vector<int>& unlabelled);

}  // namespace gasp::detail
