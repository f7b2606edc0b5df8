#pragma once
// The pair pipeline's last refinement (docs/pipeline.md, step 4): dense point-to-plane terms from
// the patches' pixels and point-to-line terms along occluding edges, re-associated over
// PairParams::dense_rounds rounds with shrinking gates, from the patch pose, then more at the last
// gate until the pose stops moving (dense_converged_m, dense_max_rounds), a round after two steps
// that agree and shrink starting ahead along them, a growing step at the last gate judged by a
// line search (the rounds' control: dense_rounds.h); with edge terms, when
// most source edge points find no target edge at the final pose, a second refinement with wider
// edge gates runs and the pose whose views agree more (visibility_check.h) is kept.
#include <optional>
#include <vector>

#include "gasp/pipeline/dense_rounds.h"
#include "gasp/pipeline/pair_registration.h"
#include "gasp/pipeline/slide_scan.h"
#include "gasp/pipeline/visibility_check.h"

namespace gasp::detail {

struct DenseOutcome {
  RegistrationResult pose;     ///< success false (with the reason) when the dense problem failed
  DenseRounds rounds;          ///< of the kept refinement
  bool wide_edge_pose = false; ///< the kept pose is the wide-edge-gate one
  double edge_paired_share = -1.0;  ///< source edge points with a target edge at the last gate (-1: not measured)
  /// The visibility check of the kept pose with the caller's parameters, when the selection
  /// between the two refinements ran it (the caller need not run it again).
  std::optional<VisibilityCheck> check;
  SlideScanReport slide;  ///< the slide scan of the kept pose (slide_scan.h)
};

/// `patch_pose` (RANSAC + patch refinement) is the start; its inlier correspondences `inliers`
/// stay in every round's problem. The outcome carries patch_pose's inlier bookkeeping.
/// `visibility`: the parameters the caller's final visibility check uses; the selection between
/// the two refinements prefers a pose that passes it, then the larger consistent share.
DenseOutcome refineDense(const DepthView& source, const DepthView& target, const RegistrationResult& patch_pose,
                         const std::vector<PatchCorrespondence>& inliers, const PairParams& params,
                         const VisibilityCheckParams& visibility);

}  // namespace gasp::detail
