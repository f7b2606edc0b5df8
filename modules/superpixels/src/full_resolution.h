#pragma once
// Full-resolution labels from the labels of the subsampled grid (SuperpixelParams::
// processing_step_px). A pixel takes the label of the cells around it (its own and the three
// nearest others) whose depth is linked to its own -- at once where they agree, by the k-means
// distance to the patches where they do not (patch borders). Then each patch keeps its largest
// linked piece, pixels left out grow into adjacent patches by plane distance, and what is still
// left becomes patches of its own or joins a neighbour when small.
#include <opencv2/core.hpp>

#include <vector>

#include "coarse_grid.h"
#include "gasp/superpixels/depth_links.h"
#include "gasp/superpixels/normals.h"

namespace gasp::detail {

struct FullResolutionLabels {
  cv::Mat labels;   ///< CV_32S, patch ids below `count` (not all used, not in raster order), -1 = none
  int count = 0;
  /// Per pixel, the grid cell whose normal (SurfaceNormals::normals of the grid) it takes; -1: none.
  std::vector<int> normal_cell;
  /// Per grid cell with a normal: the area of a pixel at depth z taking it is z^2 times this
  /// (pixel_area.h along the cell's centre ray, which is within a pixel or two of the pixel's).
  std::vector<float> cell_area_factor;
};

FullResolutionLabels refineToFullResolution(const cv::Mat& grid_labels, int grid_count, const CoarseGrid& grid,
                                            const SurfaceNormals& grid_normals, const OrganizedPointCloud& cloud,
                                            const DepthLinks& links, const CameraIntrinsics& k,
                                            const SuperpixelParams& p);

}  // namespace gasp::detail
