#pragma once
/// \file inlier_criterion.h When a patch correspondence agrees with a pose: used by RANSAC's
/// consensus and by the re-selection of inliers after refinement.
#include <vector>

#include "gasp/core/pose.h"
#include "gasp/registration/correspondence.h"

namespace gasp {

struct InlierCriterion {
  double distance_m = 0.05;       ///< max |T p_source - p_target| [m], centroid to centroid
  double normal_angle_deg = 20.0; ///< max angle between R n_source and n_target [deg]
};

/// Throws gasp::Error unless both thresholds are finite and positive (angle <= 180).
void validate(const InlierCriterion& criterion);

/// |T p_s - p_t| <= distance_m and angle(R n_s, n_t) <= normal_angle_deg.
bool isInlier(const PatchCorrespondence& c, const Isometry3& T_target_source, const InlierCriterion& criterion);

/// Indices (ascending) of the correspondences that are inliers of T_target_source.
std::vector<int> selectInliers(const std::vector<PatchCorrespondence>& correspondences,
                               const Isometry3& T_target_source, const InlierCriterion& criterion);

}  // namespace gasp
