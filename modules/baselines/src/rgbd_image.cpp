#include "gasp/baselines/rgbd_image.h"

#include "gasp/core/error.h"

namespace gasp::baselines {

void validate(const RgbdImage& view) {
  view.intrinsics.validate();
  if (view.depth_m.type() != CV_32FC1) throw Error("RgbdImage: depth_m must be CV_32FC1 [m]");
  if (view.depth_m.cols != view.intrinsics.width || view.depth_m.rows != view.intrinsics.height)
    throw Error("RgbdImage: depth_m is " + std::to_string(view.depth_m.cols) + "x" + std::to_string(view.depth_m.rows) +
                ", the intrinsics say " + std::to_string(view.intrinsics.width) + "x" +
                std::to_string(view.intrinsics.height));
  if (!view.bgr.empty() && (view.bgr.type() != CV_8UC3 || view.bgr.size() != view.depth_m.size()))
    throw Error("RgbdImage: bgr must be empty or CV_8UC3 of the depth image's size");
}

}  // namespace gasp::baselines
