#include "gasp/registration/inlier_criterion.h"

#include <cmath>

#include "gasp/core/error.h"

namespace gasp {

void validate(const InlierCriterion& criterion) {
  if (!(criterion.distance_m > 0.0) || !std::isfinite(criterion.distance_m))
    throw Error("InlierCriterion.distance_m must be positive and finite");
  if (!(criterion.normal_angle_deg > 0.0) || !(criterion.normal_angle_deg <= 180.0))
    throw Error("InlierCriterion.normal_angle_deg must be in (0, 180]");
}

bool isInlier(const PatchCorrespondence& c, const Isometry3& T_target_source, const InlierCriterion& criterion) {
  const double max_sq = criterion.distance_m * criterion.distance_m;
  if ((T_target_source * c.p_source - c.p_target).squaredNorm() > max_sq) return false;
  // cos(angle) >= cos(max angle) for unit normals.
  const double cos_max = std::cos(criterion.normal_angle_deg * M_PI / 180.0);
  return (T_target_source.linear() * c.n_source).dot(c.n_target) >= cos_max;
}

std::vector<int> selectInliers(const std::vector<PatchCorrespondence>& correspondences,
                               const Isometry3& T_target_source, const InlierCriterion& criterion) {
  std::vector<int> inliers;
  for (std::size_t i = 0; i < correspondences.size(); ++i)
    if (isInlier(correspondences[i], T_target_source, criterion)) inliers.push_back(static_cast<int>(i));
  return inliers;
}

}  // namespace gasp
