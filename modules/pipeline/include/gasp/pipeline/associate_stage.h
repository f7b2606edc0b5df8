#pragma once
/// \file associate_stage.h Stage 2 of the pair pipeline (paper III-B..E): every patch's invariant
/// neighbourhood feature set, in both views, and their restricted Damerau-Levenshtein matching
/// (association module, view_association.h). The stage keeps the feature sets: the guided
/// verification of a pose hypothesis (hypothesise_stage.h) matches them again under that pose.
#include <vector>

#include "gasp/association/feature_sets.h"
#include "gasp/association/patch_geometry.h"
#include "gasp/association/view_association.h"
#include "gasp/pipeline/depth_view.h"

namespace gasp {

/// The association module's parameters with the pipeline's defaults: k = 30 neighbours, C = 20
/// candidates on the quantile key, the mutual check, and lambda = 0.7 instead of the module's
/// 0.5 (the paper used 0.65 - 0.8 before RANSAC): RANSAC over the compatibility graph tolerates
/// the extra wrong associations, and the extra right ones are what wide baselines need.
inline AssociationParams defaultAssociateParams() {
  AssociationParams p;
  p.lambda = 0.7;
  return p;
}

/// What the stage hands on.
struct AssociatedViews {
  std::vector<PatchGeometry> source_patches, target_patches;
  std::vector<std::vector<Feature>> source_features, target_features;  ///< one feature set per patch
  /// The parameters the feature sets were made and matched with: guided matching under a pose
  /// compares them the same way.
  AssociationParams params;
  /// Mutual associations (result.associations) and one-way best partners (result.one_way); empty
  /// with result.reason when there are none.
  AssociationResult result;
  double ms = 0.0;  ///< wall time of the stage, feature sets included
};

/// Both views' feature sets (one TBB task each) and their matching. Never throws for data (a view
/// without patches gives an empty result with a reason); throws gasp::Error for invalid params.
AssociatedViews associate(const DepthView& source, const DepthView& target, const AssociationParams& params);

}  // namespace gasp
