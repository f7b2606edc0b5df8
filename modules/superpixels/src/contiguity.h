#pragma once
// Patch contiguity: each label keeps its largest 4-connected, depth-linked piece.
#include <opencv2/core.hpp>

#include <vector>

#include "gasp/superpixels/depth_links.h"

namespace gasp::detail {

/// Sets to -1 every pixel of `labels` (CV_32S) outside its label's largest linked piece (ties: the
/// piece starting first in raster order). Returns the number of pixels unlabelled; subtracts them
/// from pixel_counts[label] and appends them to `removed` when given.
int keepLargestPieces(cv::Mat& labels, const DepthLinks& links, int* pixel_counts = nullptr,
                      std::vector<int>* removed = nullptr);

}  // namespace gasp::detail
