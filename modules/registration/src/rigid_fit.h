#pragma once
// Internal: the weighted closed-form rigid fit of patch centroids.
#include <Eigen/Core>

#include <vector>

#include "gasp/core/pose.h"
#include "gasp/registration/correspondence.h"

namespace gasp::detail {

/// T minimising sum_i w_i |R p_source_i + t - p_target_i|^2 over the listed correspondences
/// (Umeyama 1991 / Kabsch without scale: R = V diag(1, 1, det(V U^T)) U^T from the SVD U S V^T of
/// the weighted cross-covariance, t = mean_target - R mean_source). Weights all zero count as 1.
Isometry3 fitRigid(const std::vector<PatchCorrespondence>& c, const std::vector<int>& indices);

}  // namespace gasp::detail
