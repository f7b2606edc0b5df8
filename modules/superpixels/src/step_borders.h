#pragma once
// Patch borders at steps: a surface a little in front of or behind a planar surface it lies on
// (a picture on a wall, a door in its frame, a mat on the floor).
//
// A step of a few cm far away is below the depth-discontinuity threshold and has the same normals
// on both sides, so the earlier stages see one smooth surface and k-means cuts it with no regard
// to the step: the patches along it straddle both levels. No pixel's depth can place the step
// there (at 4 m the Kinect noise is ~3 cm and a disparity level 4 cm), but many can:
//  1. Within each surface plane (surface_planes.h), connected runs of at least 3 interior
//     patches whose centroids lie off the plane on one side by more than step_min_sigmas robust
//     standard deviations of the members' offsets (and at least discontinuity_abs_m) form a
//     level: a plane of their own, parallel, at the run's median offset.
//  2. For two parallel planes that touch (patches adjacent, or through patches with no plane,
//     whose normals the step blurred) and whose depth difference is significant against how
//     well the planes are known yet below a depth discontinuity, the pixels along their border
//     (every pixel of a patch with no plane next to either plane or in a bridge up to 3 patches
//     wide between them, and those up to 4 px from a border between the two sides) are labelled by a minimum cut (OpenCV's GCGraph): each pixel pays the squared
//     distance of its depth to either plane in units of the pixel noise (truncated), each linked
//     pair of pixels labelled apart pays step_smoothness, the pixels around pull to their
//     patch's plane. So the step is placed where the depths of many pixels along it agree.
//  3. Each patch with no plane takes the side most of its pixels are on; pixels on the other side
//     than their patch join, through linked neighbours, a patch of their own side.
// Off by default (SuperpixelParams::borders.step_borders): +2-3 ms per fr1_xyz frame, and no gain on the
// real pair benchmarks (docs/superpixels.md).
// Patches may be left in pieces; the caller keeps each patch's largest piece and regrows the rest.
#include <vector>

#include "gasp/core/point_cloud.h"
#include "gasp/superpixels/depth_links.h"
#include "gasp/superpixels/superpixel_params.h"
#include "region_growing.h"
#include "surface_planes.h"

namespace gasp::detail {

/// As refineCreaseBorders (crease_borders.h); `planes` gains the levels. Returns the number of
/// pixels moved.
int refineStepBorders(int* L, int count, SurfacePlanes planes, const std::vector<PlaneModel>& models,
                      int* pixel_counts, int* normal_cell, const OrganizedPointCloud& cloud,
                      const DepthLinks& links, const SuperpixelParams& p);

}  // namespace gasp::detail
