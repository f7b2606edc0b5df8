#pragma once
/// \file depth_superpixels.h The depth-superpixel decomposition of one view (paper III-A):
/// normals -> smooth-surface components -> area-regularised K-means patches -> clean-up, on a grid
/// subsampled by SuperpixelParams::processing_step_px -> labels decided at full resolution ->
/// patch records and the patch adjacency graph. Calls share no state (two views can be segmented
/// at once on two threads).
#include <opencv2/core.hpp>

#include "gasp/core/view_projection.h"
#include "gasp/core/point_cloud.h"
#include "gasp/superpixels/depth_links.h"
#include "gasp/superpixels/superpixel_params.h"
#include "gasp/superpixels/surface_patch.h"

namespace gasp {

/// Decomposes a depth image [m] (CV_32FC1; 0 or NaN = no data) into surface patches in the sensor
/// frame. The projection is a pinhole's intrinsics or a range image's grid (its image holds
/// ranges; segmented at processing_step_px = 1 only). Throws gasp::Error for a wrong image type, a
/// size that differs from the projection's, or invalid parameters. An image without valid depth
/// gives an empty, valid result.
SuperpixelSegmentation segmentDepthSuperpixels(const cv::Mat& depth_m,
                                               const ViewProjection& projection,
                                               const SuperpixelParams& params = {});

/// Throws gasp::Error naming the first parameter out of its range.
void validate(const SuperpixelParams& params);

/// Patch records and adjacency from a final label image with ids 0..num_patches-1 and per-pixel
/// normals (CV_32FC3, zero where none).
void computePatchRecords(SuperpixelSegmentation& seg, int num_patches, const OrganizedPointCloud& cloud,
                         const DepthLinks& links, const cv::Mat& normals,
                         const ViewProjection& projection, const SuperpixelParams& params);

}  // namespace gasp
