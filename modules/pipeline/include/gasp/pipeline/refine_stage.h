#pragma once
/// \file refine_stage.h Stage 4 of the pair pipeline: dense refinement of a verified hypothesis.
/// Point-to-plane terms from the patches' pixels (projective association, projective_terms.h) and
/// point-to-line terms along occluding edges (edge_terms.h), gathered again at each round's pose
/// with a shrinking distance gate, solved together with the hypothesis's patch inliers; then more
/// rounds at the last gate until the pose stops moving, with extrapolation and a line search
/// (the rounds' control, dense_rounds.h). Two safeguards for slides along planes:
/// - wide edge gates: when most source edge points find no target edge at the refined pose (or
///   the refinement failed), a second refinement with wider edge gates runs, and the pose the
///   free-space test prefers is kept;
/// - the slide scan (slide_scan.h): a pose whose patch problem was degenerate is moved along the
///   unobservable directions to where the views agree more.
/// The stage does not decide whether a pose is claimed: certify_stage.h does. It asks only the
/// free-space test the pose will face, to choose between its own candidates.
#include <optional>
#include <vector>

#include "gasp/pipeline/dense_rounds.h"
#include "gasp/pipeline/depth_view.h"
#include "gasp/pipeline/edge_terms.h"
#include "gasp/pipeline/plane_hypothesis.h"
#include "gasp/pipeline/projective_terms.h"
#include "gasp/pipeline/slide_scan.h"
#include "gasp/pipeline/visibility_check.h"
#include "gasp/registration/refinement.h"

namespace gasp {

struct EdgeRefinementParams {
  bool enabled = true;  ///< edge terms in the dense rounds, gated like the pixel terms
  EdgeTermParams terms;  ///< terms.max_distance_m is replaced by each round's edge gate
  /// The second refinement's edge gates, as a factor (>= 1) of the pixel gates; 0: never.
  /// Slides larger than the pixel gates leave the edges unpaired; wide gates alone pair wrong
  /// edges in clutter, hence the choice by the free-space test.
  double wide_gate_factor = 3.0;
  /// The second refinement runs when fewer than this share (in [0, 1]) of the source edge points
  /// that land on the target's depth have a target edge within the last gate.
  double wide_min_paired_share = 0.6;
};

struct RefineParams {
  /// Rounds (3; 0 = no dense refinement), gates 0.10, 0.05, 0.03 m, then at the last gate until a
  /// round moves the source patches by less than 2 mm, at most 16 rounds; extrapolation up to 4
  /// steps; line search with up to 3 halvings (dense_rounds.h).
  DenseRoundsSettings dense;
  /// Pixel terms: every 8th pixel, normals within 20 deg (max_distance_m is replaced by the
  /// round's gate).
  ProjectiveTermParams pixels;
  EdgeRefinementParams edges;
  /// The solver: Huber 0.02 m, sigma 0.01 m. Degeneracy by the eigenvalue ratio 1e-3 (and
  /// 0.05 m): the thousands of pixel terms are not independent, so their absolute standard
  /// deviations are optimistic and only the ratio separates a plane (about 1e-4) from a scene.
  /// Partial poses on: a round that leaves up to three directions unobservable moves the pose in
  /// the observed ones only, and the rounds go on (the certificate decides what is claimed).
  RefinementParams solver = defaultSolver();
  SlideScanParams slide_scan;

  static RefinementParams defaultSolver() {
    RefinementParams p;
    p.degeneracy = DegeneracyParams{1e-3, 0.05};
    p.partial_poses = true;
    return p;
  }
};

/// Throws gasp::Error naming the first invalid parameter.
void validate(const RefineParams& params);

/// What the stage did.
struct Refinement {
  /// success false (with the reason) when the dense problem failed; degenerate when it ended
  /// unobservable. Carries the hypothesis's inlier bookkeeping and RANSAC timings.
  RegistrationResult pose;
  DenseRounds rounds;           ///< of the kept refinement
  bool wide_edge_pose = false;  ///< the kept pose is the wide-edge one
  double edge_paired_share = -1.0;  ///< source edge points with a target edge at the last gate (-1: not measured)
  /// The free-space test of the kept pose, when the stage ran it (the certificate need not run it
  /// again).
  std::optional<VisibilityCheck> check;
  SlideScanReport slide;  ///< the slide scan of the kept pose (slide.ran false: not needed)
};

/// Refines `hypothesis` (RANSAC + patch refinement), whose inlier correspondences `inliers` stay
/// in every round. `free_space(T)`: the test a claimed pose will face (certify_stage.h).
/// `target_plane`: the target view's dominant plane when already found (plane_hypothesis.h; a
/// partial pose's slide scan searches along it; null: found here when needed). `target_edges`:
/// the target's edge targets when built before from `target` with params.edges.terms (a
/// keyframe's, for every frame tracked against it; null: built here when edge terms are on).
/// Requires params.dense.rounds > 0. Never throws for data.
Refinement refine(const DepthView& source, const DepthView& target, const RegistrationResult& hypothesis,
                  const std::vector<PatchCorrespondence>& inliers, const RefineParams& params,
                  const FreeSpaceTest& free_space, const DominantPlane* target_plane = nullptr,
                  const EdgeTargets* target_edges = nullptr);

}  // namespace gasp
