#include "pixel_keypoints.h"

#include <opencv2/imgproc.hpp>

#include <cmath>

#include "gasp/core/error.h"
#include "surface_cloud.h"

namespace gasp::baselines {

DescribedKeypoints liftPixelKeypoints(const RgbdImage& view, const std::vector<cv::KeyPoint>& keypoints,
                                      const cv::Mat& descriptors, const SurfaceParams& surface) {
  if (descriptors.rows != static_cast<int>(keypoints.size()) || (!descriptors.empty() && descriptors.type() != CV_32F))
    throw Error("liftPixelKeypoints: one CV_32F descriptor row per keypoint expected");
  const SurfaceCloud s = makeSurfaceCloud(view, surface);
  DescribedKeypoints out;
  out.descriptors.create(0, descriptors.cols, CV_32F);
  std::vector<int> rows;
  for (std::size_t k = 0; k < keypoints.size(); ++k) {
    const int u = static_cast<int>(std::lround(keypoints[k].pt.x));
    const int v = static_cast<int>(std::lround(keypoints[k].pt.y));
    if (u < 0 || v < 0 || u >= view.depth_m.cols || v >= view.depth_m.rows) continue;
    const float z = view.depth_m.at<float>(v, u);
    if (!(z > 0) || !(z <= surface.max_depth_m)) continue;
    const Eigen::Vector3d p = view.intrinsics.unproject(u, v, z);
    const int i = nearestWithNormal(s, p.cast<float>(), 2.0 * surface.voxel_m);
    if (i < 0) continue;
    const auto& n = (*s.normals)[static_cast<std::size_t>(i)];
    out.points.push_back(p);
    out.normals.push_back(Eigen::Vector3d(n.normal_x, n.normal_y, n.normal_z).normalized());
    out.pixels.push_back(keypoints[k].pt);
    rows.push_back(static_cast<int>(k));
  }
  out.descriptors.create(static_cast<int>(rows.size()), descriptors.cols, CV_32F);
  for (std::size_t r = 0; r < rows.size(); ++r) descriptors.row(rows[r]).copyTo(out.descriptors.row(static_cast<int>(r)));
  return out;
}

cv::Mat greyImage(const RgbdImage& view, const char* who) {
  validate(view);
  if (view.bgr.empty()) throw Error(std::string(who) + " needs the view's colour image (none given)");
  cv::Mat grey;
  cv::cvtColor(view.bgr, grey, cv::COLOR_BGR2GRAY);
  return grey;
}

}  // namespace gasp::baselines
