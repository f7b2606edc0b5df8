#include "gasp/superpixels/patch_repeatability.h"

#include <cmath>

#include "gasp/core/depth_image.h"
#include "gasp/core/error.h"

namespace gasp {

RepeatabilityResult measureRepeatability(const SuperpixelSegmentation& a, const SuperpixelSegmentation& b,
                                         const cv::Mat& depth_b, const ViewProjection& k,
                                         const Isometry3& T_b_a, const RepeatabilityParams& p) {
  if (depth_b.type() != CV_32FC1 || depth_b.cols != k.width() || depth_b.rows != k.height())
    throw Error("measureRepeatability: depth_b must be CV_32FC1 of the intrinsics' size");
  const double min_cos = std::cos(p.max_normal_angle_deg * M_PI / 180.0);
  RepeatabilityResult r;
  r.patches_a = static_cast<int>(a.patches.size());
  for (const auto& pa : a.patches) {
    const Eigen::Vector3d c = T_b_a * pa.centroid;
    const Eigen::Vector3d n = T_b_a.linear() * pa.normal;
    double u = 0, v = 0;
    if (!k.project(c, u, v)) continue;
    const int ui = static_cast<int>(std::floor(u + 0.5)), vi = static_cast<int>(std::floor(v + 0.5));
    if (ui < 0 || vi < 0 || ui >= k.width() || vi >= k.height()) continue;
    const float z = depth_b.at<float>(vi, ui);
    const double zc = k.depth(c);
    if (!isValidDepth(z) || std::abs(z - zc) > p.visibility_tolerance_m + p.visibility_tolerance_rel * zc)
      continue;
    if (n.dot(c) >= 0.0) continue;  // seen from behind
    ++r.in_overlap;
    const double ra = pa.radius();
    for (const auto& pb : b.patches) {
      const double reach = 0.5 * (ra + pb.radius());
      if ((pb.centroid - c).squaredNorm() <= reach * reach && pb.normal.dot(n) >= min_cos) {
        ++r.repeated;
        break;
      }
    }
  }
  return r;
}

}  // namespace gasp
