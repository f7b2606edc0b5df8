#include "gasp/pipeline/depth_view.h"

#include <tbb/parallel_invoke.h>

#include <tuple>

#include "gasp/core/undistortion.h"
#include "gasp/superpixels/depth_superpixels.h"

namespace gasp {

DepthView makeDepthView(const cv::Mat& depth_m, const CameraIntrinsics& intrinsics, const SuperpixelParams& params) {
  DepthView v;
  std::tie(v.depth_m, v.intrinsics) = pinholeDepth(depth_m, intrinsics);
  v.segmentation = segmentDepthSuperpixels(v.depth_m, v.intrinsics, params);
  v.superpixels = params;
  return v;
}

std::pair<DepthView, DepthView> makeDepthViews(const cv::Mat& depth_a, const cv::Mat& depth_b,
                                               const CameraIntrinsics& intrinsics, const SuperpixelParams& params) {
  std::pair<DepthView, DepthView> views;
  tbb::parallel_invoke([&] { views.first = makeDepthView(depth_a, intrinsics, params); },
                       [&] { views.second = makeDepthView(depth_b, intrinsics, params); });
  return views;
}

}  // namespace gasp
