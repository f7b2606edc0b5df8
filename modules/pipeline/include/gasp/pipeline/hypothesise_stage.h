#pragma once
/// \file hypothesise_stage.h Stage 3 of the pair pipeline: a pose hypothesis from one set of patch
/// associations. RANSAC over the associated centroids, then point-to-plane refinement with the
/// patch normals on its inliers, re-selecting them at the refined pose (registration module,
/// register_patches.h); then guided verification: at that pose every source patch looks for a
/// target patch near its mapped centroid whose feature set agrees (guided_association.h), and a
/// hypothesis that too few patches agree with is refused.
#include <string>
#include <vector>

#include "gasp/association/guided_association.h"
#include "gasp/pipeline/associate_stage.h"
#include "gasp/registration/register_patches.h"

namespace gasp {

struct GuidedVerificationParams {
  bool enabled = true;
  GuidedAssociationParams gates;  ///< 0.035 m, 20 deg, lambda 0.8
  int min_support = 12;           ///< source patches with an agreeing partner at the pose (>= 3)
  /// Run RANSAC and the patch refinement again on the guided associations (instead of the first
  /// set's inliers). Off: where a floor dominates the view, its many guided associations outweigh
  /// the objects that fix the pose.
  bool densify = false;
};

struct HypothesiseParams {
  /// RANSAC (0.05 m / 20 deg inliers, at least 8) and the patch refinement (Huber 0.02 m,
  /// sigma 0.01 m). The degeneracy ratio is 1e-3 instead of the registration module's 1e-2: the
  /// views' own degeneracy is caught before (certify_stage.h), and floor-dominated views whose
  /// centroid fit does fix the in-plane directions reach only a few 1e-3.
  PoseEstimationParams pose = defaultPose();
  GuidedVerificationParams guided;

  static PoseEstimationParams defaultPose() {
    PoseEstimationParams p;
    p.refinement.degeneracy.min_eigenvalue_ratio = 1e-3;
    return p;
  }
};

/// Throws gasp::Error naming the first invalid parameter.
void validate(const HypothesiseParams& params);

struct Hypothesis {
  std::vector<PatchAssociation> used;  ///< the associations it was estimated from
  std::vector<PatchCorrespondence> correspondences;  ///< one per entry of `used`, same order
  /// The estimate; pose.success false with the reason when RANSAC, the refinement or the guided
  /// verification refused it. A pose whose patch problem is degenerate but has inliers is a
  /// hypothesis too (found() true): the dense rounds may observe what the patches did not.
  RegistrationResult pose;
  bool verified = false;  ///< found() and, when enabled, the guided verification passed
  /// Guided associations at the pose (enabled only; sorted by source patch).
  std::vector<PatchAssociation> guided;
  int guided_support = -1;  ///< guided.size() (-1: verification not reached)
  double ransac_ms = 0, refine_ms = 0, guided_ms = 0;

  bool found() const { return pose.success || (pose.degenerate && !pose.inliers.empty()); }
};

/// The hypothesis from `used` (indices into a's patches). Never throws for data.
Hypothesis hypothesise(const AssociatedViews& a, std::vector<PatchAssociation> used, const HypothesiseParams& params);

/// The guided associations of a's patches at T_target_source (guided_association.h).
std::vector<PatchAssociation> guidedAt(const AssociatedViews& a, const Isometry3& T_target_source,
                                       const GuidedVerificationParams& params);

}  // namespace gasp
