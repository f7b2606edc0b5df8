#pragma once
/// \file area_kmeans.h Splits smooth surfaces into compact patches of similar surface area
/// (paper III-A): about area / target area clusters per surface, seeded uniformly over the surface
/// (Poisson-disk dart throwing in 3D; the paper seeds "similar to k-means++", which spreads seeds
/// the same way at O(n K) cost instead of O(n)), refined by Lloyd iterations on 3D position
/// and normal, each centre searching only the pixels in an image window around its projection
/// (as SLIC does), which keeps an iteration linear in the pixel count.
#include <opencv2/core.hpp>

#include "gasp/core/view_projection.h"
#include "gasp/core/point_cloud.h"
#include "gasp/superpixels/normals.h"

namespace gasp {

struct AreaPatches {
  cv::Mat labels;  ///< CV_32S patch id, -1 where there is no region or no centre reached the pixel
  int count = 0;
};

/// region_labels: CV_32S ids 0..num_regions-1 (-1 = none). Deterministic for params.seed.
AreaPatches splitIntoAreaPatches(const cv::Mat& region_labels, int num_regions,
                                 const OrganizedPointCloud& cloud, const SurfaceNormals& normals,
                                 const ViewProjection& intrinsics, const SuperpixelParams& params);

}  // namespace gasp
