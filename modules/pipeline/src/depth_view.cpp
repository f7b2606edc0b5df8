#include "gasp/pipeline/depth_view.h"

#include "gasp/superpixels/depth_superpixels.h"

namespace gasp {

DepthView makeDepthView(const cv::Mat& depth_m, const CameraIntrinsics& intrinsics, const SuperpixelParams& params) {
  DepthView v;
  v.depth_m = depth_m;
  v.intrinsics = intrinsics;
  v.segmentation = segmentDepthSuperpixels(depth_m, intrinsics, params);
  return v;
}

}  // namespace gasp
