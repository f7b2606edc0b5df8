#pragma once
// The subsampled grid the segmentation works on (SuperpixelParams::processing_step_px): each cell
// of s x s pixels holds the mean point of the block's nearest surface, so thin foreground
// structures survive and no point mixes two surfaces across a depth edge.
#include "gasp/core/camera_intrinsics.h"
#include "gasp/core/point_cloud.h"
#include "gasp/superpixels/superpixel_params.h"

namespace gasp::detail {

struct CoarseGrid {
  int step = 1;
  OrganizedPointCloud cloud;     ///< ceil(w / s) x ceil(h / s) cells
  CameraIntrinsics intrinsics;   ///< of the grid: f / s, principal point moved to cell centres
  SuperpixelParams params;       ///< pixel sizes and counts scaled to cells
};

/// p.processing_step_px must be >= 2.
CoarseGrid makeCoarseGrid(const OrganizedPointCloud& full, const CameraIntrinsics& k, const SuperpixelParams& p);

}  // namespace gasp::detail
