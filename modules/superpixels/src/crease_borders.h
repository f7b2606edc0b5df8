#pragma once
// Patch borders along creases, decided where the planes of the two surfaces meet.
//
// Near a crease (two walls, a wall and the floor, two faces of a box) pixel normals are blurred by
// their window and depths are noisy (a few cm at 4 m), so the per-pixel decisions of the earlier
// stages leave borders 1-3 px off the true edge -- 10-30 % of a far patch. The planes of the two
// surfaces, fitted over many patches (surface_planes.h), are known to a few mm; along a pixel's ray
// the visible surface is the one on its own side of the other plane (the nearer hit at a concave
// crease, the farther at a convex one), which needs no depth of the pixel at all. So border pixels
// between patches whose planes meet at more than crease_min_angle_deg move to the adjacent patch
// whose surface their ray sees, in sweeps (at most crease_band_px), when their depth is linked to
// that plane's (depth_links.h rule). A pixel of a patch with no plane moves only when its ray sees
// the target's surface against every crease neighbour's.
// Patches may be left in pieces; the caller keeps each patch's largest piece and regrows the rest.
#include <vector>

#include "gasp/core/camera_intrinsics.h"
#include "gasp/core/point_cloud.h"
#include "gasp/superpixels/depth_links.h"
#include "gasp/superpixels/superpixel_params.h"
#include "region_growing.h"
#include "surface_planes.h"

namespace gasp::detail {

/// L: full-resolution labels (-1 = none) below `count`; planes: findSurfacePlanes() of L; models:
/// each label's centroid and mean pixel normal; pixel_counts: per label, updated; normal_cell: per
/// pixel, the grid cell whose normal it takes, updated for moved pixels (the cell of the neighbour
/// it joins through). Returns the number of pixels moved.
int refineCreaseBorders(int* L, int count, const SurfacePlanes& planes, const std::vector<PlaneModel>& models,
                        int* pixel_counts, int* normal_cell, const OrganizedPointCloud& cloud,
                        const DepthLinks& links, const CameraIntrinsics& k, const SuperpixelParams& p);

}  // namespace gasp::detail
