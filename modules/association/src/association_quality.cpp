#include "gasp/association/association_quality.h"

#include <cmath>

#include "gasp/superpixels/patch_repeatability.h"

namespace gasp {

bool isSameSurface(const SurfacePatch& a, const SurfacePatch& b, const Isometry3& T_b_a, double max_angle_deg) {
  const Eigen::Vector3d c = T_b_a * a.centroid;
  const Eigen::Vector3d n = T_b_a.linear() * a.normal;
  const double reach = 0.5 * (a.radius() + b.radius());
  return (c - b.centroid).squaredNorm() <= reach * reach &&
         n.dot(b.normal) >= std::cos(max_angle_deg * M_PI / 180.0);
}

AssociationQuality evaluateAssociations(const std::vector<PatchAssociation>& associations,
                                        const SuperpixelSegmentation& a, const SuperpixelSegmentation& b,
                                        const cv::Mat& depth_b, const CameraIntrinsics& k, const Isometry3& T_b_a) {
  AssociationQuality q;
  for (const auto& s : associations) {
    ++q.associations;
    q.correct += isSameSurface(a.patches.at(static_cast<std::size_t>(s.a)),
                               b.patches.at(static_cast<std::size_t>(s.b)), T_b_a);
  }
  RepeatabilityParams rp;
  rp.max_normal_angle_deg = kCorrectAssociationMaxNormalAngleDeg;
  q.with_true_partner = measureRepeatability(a, b, depth_b, k, T_b_a, rp).repeated;
  return q;
}

}  // namespace gasp
