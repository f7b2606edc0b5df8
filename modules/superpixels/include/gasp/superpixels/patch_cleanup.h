#pragma once
/// \file patch_cleanup.h Post-processing of area patches (paper III-A, last step), in order:
/// 1. contiguity: each patch keeps its largest 4-connected, depth-connected piece;
/// 2. leftover valid pixels (edges, creases, small components, cut-off pieces) join adjacent
///    patches by priority region growing (a bucket queue over the cost): cost = distance to the
///    patch plane + a normal-mismatch term, accepted up to two patch radii, a patch growing to at
///    most three times the target area; growth only crosses depth-connected 4-neighbours, so
///    patches stay contiguous;
/// 3. what is still left forms new regions, split like the smooth surfaces;
/// 4. patches below the minimum size are merged into the adjacent patch with the most similar
///    normal (edge contraction on the patch graph), or dropped when they have no neighbour.
/// The pixels that end in no patch are counted as dropped noise.
#include <opencv2/core.hpp>

#include "gasp/core/view_projection.h"
#include "gasp/core/point_cloud.h"
#include "gasp/superpixels/normals.h"

namespace gasp {

/// Cleans `labels` (CV_32S, -1 = none) in place and relabels patches 0..n-1 in raster order;
/// returns n.
int cleanUpPatches(cv::Mat& labels, const OrganizedPointCloud& cloud, const DepthLinks& links,
                   const SurfaceNormals& normals, const ViewProjection& intrinsics,
                   const SuperpixelParams& params);

}  // namespace gasp
