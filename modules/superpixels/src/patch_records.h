#pragma once
// Patch records (surface_patch.h) from a label image: one pass over the pixels, moments
// accumulated per run of one label in a row; adjacency from the depth links across labels.
#include "gasp/core/view_projection.h"
#include "gasp/core/point_cloud.h"
#include "gasp/superpixels/depth_links.h"
#include "gasp/superpixels/superpixel_params.h"
#include "gasp/superpixels/surface_patch.h"
#include "region_growing.h"

namespace gasp::detail {

/// Patches, adjacency and pixel counts of seg.labels, whose ids are below label_bound. With
/// `relabel`, ids become 0..n-1 in raster order of first pixel, rewritten in the same pass; else
/// they must already be 0..label_bound-1 (all used). cell_area_factor: with pixels that take the
/// normal of a grid cell (normal_of.cell), the area of such a pixel is z^2 * cell_area_factor[cell]
/// (pixel_area.h at the cell's centre ray; saves a square root and a division per pixel).
void recordPatches(SuperpixelSegmentation& seg, int label_bound, const OrganizedPointCloud& cloud,
                   const DepthLinks& links, const PixelNormals& normal_of, const ViewProjection& k,
                   const SuperpixelParams& p, bool relabel, const float* cell_area_factor = nullptr);

}  // namespace gasp::detail
