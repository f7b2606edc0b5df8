#pragma once
/// \file register_patches.h The relative pose of two views from their patch associations:
/// RANSAC over centroids (ransac.h), then point-to-plane refinement on the RANSAC inliers
/// (refinement.h); after each refinement the inliers are re-selected at the refined pose with
/// the RANSAC criterion and, if they changed, the refinement is repeated (reselection_rounds).
/// With refine = false the RANSAC pose is only evaluated (residuals, information, degeneracy),
/// so RANSAC-only results are never claimed along unobservable directions either.
#include <vector>

#include "gasp/registration/correspondence.h"
#include "gasp/registration/ransac.h"
#include "gasp/registration/refinement.h"
#include "gasp/registration/registration_result.h"

namespace gasp {

struct PoseEstimationParams {
  RansacParams ransac;          ///< its inlier criterion also re-selects inliers after refinement
  RefinementParams refinement;  ///< Huber 0.02 m, sigma 0.01 m, degeneracy ratio 1e-2
  bool refine = true;           ///< false: RANSAC only (benchmarks compare both)
  int reselection_rounds = 2;   ///< extra refine rounds after re-selecting inliers (>= 0)
};

/// Throws gasp::Error naming the first invalid parameter.
void validate(const PoseEstimationParams& params);

/// T_target_source from patch correspondences (and optional dense terms used in every
/// refinement). inliers index into `correspondences`; ransac_ms and refine_ms time the stages.
/// Bad input or no consensus: success = false with a reason; never throws for data.
RegistrationResult estimatePose(const std::vector<PatchCorrespondence>& correspondences,
                                const PoseEstimationParams& params = {}, const std::vector<PointToPlane>& dense = {});

}  // namespace gasp
