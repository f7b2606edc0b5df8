#pragma once
/// \file superpixel_params.h Parameters of the depth-superpixel decomposition (paper III-A),
/// with defaults for a Kinect-class sensor at 640x480, grouped by what they shape: the smooth
/// surfaces, the area-regularised clustering, the clean-up and the borders. Units are in the
/// names; sizes in pixels are full-resolution pixels (the pipeline scales them when it works on a
/// subsampled grid). Each leaf's name is its key in the params file (section `segment`).
#include <cstdint>

namespace gasp {

/// Depth connectivity, normals and smooth-surface components.
struct SmoothSurfaceParams {
  /// 4-neighbours are on one surface only when |z1 - z2| <= discontinuity_abs_m +
  /// discontinuity_rel * z^2 (Kinect depth steps grow with z^2).
  double discontinuity_abs_m = 0.01;
  double discontinuity_rel = 0.02;  ///< [1/m]
  /// Normals from smoothed 3D gradients over a depth-adaptive square window that never crosses a
  /// discontinuity (integral images). Window half-size: normal_window_px_per_m * z pixels (the
  /// window widens with depth, as Kinect noise grows with z^2), clamped to [normal_min_radius_px,
  /// normal_max_radius_px] and to the distance to the nearest discontinuity; pixels closer than
  /// normal_min_radius_px to one get no normal.
  double normal_window_px_per_m = 6.0;
  int normal_min_radius_px = 2;
  int normal_max_radius_px = 12;
  /// Pixels whose normals across their window differ by more than max_crease_angle_deg (creases,
  /// corners) are set aside and re-added after patching.
  double max_crease_angle_deg = 25.0;
  double max_neighbour_normal_angle_deg = 10.0;  ///< between 4-neighbours inside a component
  int min_component_pixels = 40;                 ///< smaller components are set aside too
};

/// Area-regularised patches: K-means seeded uniformly over the surface.
struct KmeansParams {
  int kmeans_iterations = 6;
  double kmeans_normal_weight = 0.5;  ///< weight of (1 - n.n_c) against (distance / patch radius)^2
  int seed_sampling_step_px = 2;      ///< seeds are drawn from every n-th pixel (each direction)
  std::uint64_t seed = 1;             ///< random seed of the seeding order (deterministic)
  int kmeans_iteration_step_px = 2;   ///< Lloyd iterations assign every n-th pixel each way (the final pass all)
  int kmeans_coarse_iterations = 4;   ///< the first of the kmeans_iterations assign every (2 n)-th pixel
};

/// Clean-up: patches below min_patch_pixels or min_patch_area_ratio * target area are merged into
/// the most similar adjacent patch; leftover pixels join adjacent patches by proximity and normal
/// (priority region growing, depth-connected only).
struct CleanupParams {
  int min_patch_pixels = 20;
  double min_patch_area_ratio = 0.25;
  double regrow_normal_weight_m = 0.1;  ///< cost of a 90 deg normal mismatch, as a distance [m]
};

/// Borders between patches of different planes.
struct BorderParams {
  /// Crease borders (src/crease_borders.h; with processing_step_px > 1): border pixels between
  /// patches of two planar surfaces meeting at more than crease_min_angle_deg move to the patch
  /// whose plane their ray sees, up to crease_band_px pixels from the border. Surface planes are
  /// groups of coplanar patches: centroids within plane_noise_abs_m + plane_noise_rel * z^2 (RMS)
  /// of the group's plane.
  bool crease_borders = true;
  double crease_min_angle_deg = 30.0;
  int crease_band_px = 8;
  double plane_noise_abs_m = 0.005;
  double plane_noise_rel = 0.003;  ///< [1/m]
  /// Step borders (src/step_borders.h; with crease_borders): patches of a surface plane whose
  /// centroids lie more than step_min_sigmas robust standard deviations off it (and at least
  /// discontinuity_abs_m) form a level (a picture on a wall); the border between the level and
  /// the surface is placed by a minimum cut over depth residuals, a linked pair of pixels on
  /// different sides costing step_smoothness (in units of a pixel's squared-noise cost).
  bool step_borders = false;  ///< off by default: no gain on real pairs (docs/superpixels.md)
  double step_min_sigmas = 6.0;
  double step_smoothness = 1.0;
};

struct SuperpixelParams {
  double target_patch_area_m2 = 0.004;  ///< ~6.3 x 6.3 cm; a desk frame gives a few hundred patches
  /// Normals, components, k-means and clean-up run on a grid subsampled by processing_step_px each
  /// way (a cell holds the mean point of the nearest surface in its block), 4x fewer pixels at 2;
  /// labels are then decided at full resolution where the cells around a pixel disagree or lie
  /// across a depth edge. 1 = every stage at full resolution (about 2.5x slower, quality about the
  /// same; docs/superpixels.md). At most 4.
  int processing_step_px = 2;
  double max_incidence_deg = 80.0;  ///< foreshortening of a pixel's area is clamped at this angle
  SmoothSurfaceParams surfaces;
  KmeansParams kmeans;
  CleanupParams cleanup;
  BorderParams borders;
};

}  // namespace gasp
