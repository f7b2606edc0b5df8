#pragma once
/// \file area_kmeans.h Splits smooth surfaces into compact patches of similar surface area
/// (paper III-A): K = round(area / target area) clusters per surface, seeded k-means++ style over
/// the surface (D^2 sampling weighted by pixel area), refined by Lloyd iterations on 3D position
/// and normal, each centre searching only the pixels in an image window around its projection
/// (as SLIC does), which keeps an iteration linear in the pixel count.
#include <opencv2/core.hpp>

#include "gasp/core/camera_intrinsics.h"
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
                                 const CameraIntrinsics& intrinsics, const SuperpixelParams& params);

}  // namespace gasp
