#pragma once
// Planar surfaces of a labelling, found from its patches (shared by the crease and step border
// stages, crease_borders.h and step_borders.h):
//  1. interior patches (every depth-linked neighbour's normal within max_neighbour_normal_angle_deg)
//     are grouped by union-find into planar surfaces (normals within that angle, centroids on each
//     other's plane within plane_noise); a group of at least 3 patches whose centroids lie on the
//     group's plane (pixel-weighted mean normal and centroid, RMS within plane_noise) is a surface
//     plane;
//  2. patches left out (those along a crease) take the plane of an adjacent group they lie on
//     (the nearest, normals within the same angle).
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "gasp/superpixels/depth_links.h"
#include "gasp/superpixels/superpixel_params.h"
#include "region_growing.h"

namespace gasp::detail {

struct SurfacePlane {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  ///< unit, facing the camera
  double offset = 0.0;                               ///< normal . point
};

struct SurfacePlanes {
  std::vector<std::vector<int>> adjacency;  ///< per label, the labels it is depth-linked to (sorted)
  std::vector<std::uint8_t> border;         ///< per pixel, 1 on either side of such a link
  std::vector<std::uint8_t> interior;       ///< per label, step 1's interior patches
  std::vector<SurfacePlane> planes;
  std::vector<int> plane_of;  ///< per label, index into planes (-1: none); `interior` says how
};

/// L: labels (-1 = none) below `count`; models: each label's centroid and mean pixel normal (zero
/// normal: unknown); pixel_counts: per label.
SurfacePlanes findSurfacePlanes(const int* L, int count, const std::vector<PlaneModel>& models,
                                const int* pixel_counts, const DepthLinks& links, const SuperpixelParams& p);

}  // namespace gasp::detail
