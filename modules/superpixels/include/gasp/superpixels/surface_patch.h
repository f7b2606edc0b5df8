#pragma once
/// \file surface_patch.h A depth superpixel (surface patch) and a whole decomposition of a view.
#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <cstddef>
#include <vector>

namespace gasp {

/// One regularised surface patch, in the camera frame of its view.
struct SurfacePatch {
  int id = -1;                                     ///< index in SuperpixelSegmentation::patches
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();  ///< mean of its points [m]
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();    ///< mean of point normals, unit, towards the camera
  double area_m2 = 0.0;                            ///< surface area (foreshortened pixel areas) [m^2]
  int pixel_count = 0;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();  ///< of its points [m^2]
  double planarity = 0.0;  ///< 1 - lambda_min / lambda_mid of the covariance (1 = flat)
  cv::Rect bbox;           ///< pixel bounding box

  /// Radius of a disc of the patch's area [m].
  double radius() const;
};

/// Pixel counts of a decomposition.
struct SegmentationStats {
  std::size_t valid_pixels = 0;     ///< pixels with valid depth
  std::size_t assigned_pixels = 0;  ///< valid pixels inside a patch
  std::size_t dropped_pixels = 0;   ///< valid pixels left out as noise (isolated, flying pixels)
  double coverage() const {
    return valid_pixels ? static_cast<double>(assigned_pixels) / static_cast<double>(valid_pixels) : 0.0;
  }
};

/// Wall-clock time per stage [ms]. cloud: back-projection, depth links and the subsampled grid;
/// refine: full-resolution labels from the grid's (0 with processing_step_px = 1).
struct SegmentationTimings {
  double cloud_ms = 0, normals_ms = 0, components_ms = 0, kmeans_ms = 0, cleanup_ms = 0,
         patches_ms = 0, refine_ms = 0;  // refine_ms last: positional initialisation still compiles
  double total() const {
    return cloud_ms + normals_ms + components_ms + kmeans_ms + cleanup_ms + refine_ms + patches_ms;
  }
};

/// The decomposition of one depth image into patches.
struct SuperpixelSegmentation {
  cv::Mat labels;  ///< CV_32S, patch id per pixel, -1 = no patch (no depth or dropped)
  std::vector<SurfacePatch> patches;
  /// adjacency[i]: ids of patches sharing a depth-connected 4-neighbour boundary with i (sorted).
  std::vector<std::vector<int>> adjacency;
  SegmentationStats stats;
  SegmentationTimings timings;
};

}  // namespace gasp
