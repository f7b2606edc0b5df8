#include "gasp/pipeline/depth_view.h"

#include <tbb/parallel_invoke.h>

#include <tuple>

#include "gasp/core/undistortion.h"
#include "gasp/superpixels/depth_superpixels.h"

namespace gasp {

DepthView makeDepthView(const cv::Mat& depth_m, const CameraIntrinsics& intrinsics, const SuperpixelParams& params) {
  DepthView v;
  CameraIntrinsics pinhole;
  std::tie(v.depth_m, pinhole) = pinholeDepth(depth_m, intrinsics);
  v.projection = pinhole;
  v.segmentation = segmentDepthSuperpixels(v.depth_m, v.projection, params);
  v.superpixels = params;
  return v;
}

DepthView makeDepthView(const cv::Mat& depth_m, const ViewProjection& projection, const SuperpixelParams& params) {
  if (projection.isPinhole()) return makeDepthView(depth_m, projection.pinhole(), params);
  DepthView v;
  v.depth_m = depth_m;
  v.projection = projection;
  v.segmentation = segmentDepthSuperpixels(v.depth_m, v.projection, params);
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
