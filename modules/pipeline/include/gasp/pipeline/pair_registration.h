#pragma once
/// \file pair_registration.h The whole GASP front-end for one pair of depth views: patch
/// associations (paper III-B..E, association module), RANSAC over the associated centroids and
/// point-to-plane refinement with the patch normals (registration module), then an optional
/// dense refinement: projective point-to-plane terms from the patches' pixels
/// (projective_terms.h), re-associated at each round with a shrinking distance gate.
/// The result is what a SLAM system consumes: T_target_source with its information matrix, or
/// no estimate with the reason (too few associations, no consensus, degenerate geometry).
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "gasp/association/guided_association.h"
#include "gasp/association/view_association.h"
#include "gasp/pipeline/depth_view.h"
#include "gasp/pipeline/edge_terms.h"
#include "gasp/pipeline/model_error.h"
#include "gasp/pipeline/projective_terms.h"
#include "gasp/pipeline/slide_scan.h"
#include "gasp/pipeline/view_degeneracy.h"
#include "gasp/pipeline/visibility_check.h"
#include "gasp/registration/register_patches.h"

namespace gasp {

struct PairParams {
  /// Used by callers that build the views (makeDepthView). registerViews() itself does not use
  /// it: the finer-scale retry re-segments each view with its own DepthView::superpixels.
  SuperpixelParams superpixels;
  /// Checked first: a view whose own geometry cannot fix a pose (one plane, parallel planes)
  /// gives no estimate with degenerate = true, whatever the associations.
  ViewDegeneracyParams view_degeneracy;
  /// k 30, C 20 (quantile key), mutual check, and lambda 0.7 instead of the association
  /// module's 0.5: RANSAC over the compatibility graph tolerates the extra wrong associations,
  /// and the extra right ones cut the failures at wide baselines (fr1_xyz skip 30: 15 % -> 3 %,
  /// skip 50: 32 % -> 18 %, fr3_cabinet_kf skip 2: 4 % -> 0 %; docs/pipeline.md). The paper
  /// used 0.65 - 0.8.
  AssociationParams association = defaultAssociation();
  /// RANSAC 0.05 m / 20 deg, Huber 0.02 m; degeneracy ratio 1e-3 instead of the registration
  /// module's 1e-2: a scene's true degeneracy is caught by view_degeneracy first, and the
  /// inliers of a floor-dominated view (fr3_cabinet) reach only 2e-3 - 5e-3 while their
  /// centroid-to-centroid RANSAC fit does fix the in-plane directions.
  PoseEstimationParams pose = defaultPoseParams();
  /// When the mutual associations give no pose, or one that fails the guided verification, try
  /// again with the one-way best partners added (AssociationResult::one_way): more right
  /// associations at wide baselines, more wrong ones too; such a pose is verified the same way.
  bool one_way_fallback = true;
  /// The visibility check's violation limit for a pose found with the one-way fallback (the
  /// lower of this and visibility.max_violation_ratio). On the pair benchmark's fr1_xyz pairs
  /// from every 10th frame (skips 10-100) and fr3_cabinet_kf, every right fallback pose stays at
  /// or below 0.034; wrong fallback poses had 0.14 (280 -> 310 with step borders, 0.20 m /
  /// 14 deg off), 0.16 (430 -> 530, 1.0 m / 105 deg) and 0.29 (docs/pipeline.md).
  double one_way_max_violation_ratio = 0.08;
  /// Guided verification (guided_association.h): at the pose estimatePose() gives (RANSAC and
  /// the patch refinement), every source patch looks for a target patch near its mapped centroid
  /// whose feature set agrees (D_hat <= guided.lambda). Fewer than min_guided_support such
  /// patches: no estimate. The guided associations at the final pose are PairResult::verified.
  bool guided_verification = true;
  /// Also refine on the guided associations instead of the RANSAC inliers (RANSAC and the patch
  /// refinement run again on them). Off: measured slightly worse on fr3_cabinet_kf, where the
  /// floor's many guided associations outweigh the cabinet (docs/pipeline.md).
  bool guided_densify = false;
  GuidedAssociationParams guided;  ///< 0.035 m, 20 deg, lambda 0.8
  int min_guided_support = 12;
  bool refine = true;               ///< false: RANSAC pose only (no patch or dense refinement)
  /// Dense rounds after the patch refinement (0 = none). Each round re-associates the pixels at
  /// the current pose; the distance gate of round k is dense_gates_m[min(k, size - 1)] [m].
  int dense_rounds = 3;
  std::vector<double> dense_gates_m{0.10, 0.05, 0.03};
  /// After the dense_rounds rounds, more rounds at the last gate until one moves the source
  /// patches by less than dense_converged_m (RMS displacement of their centroids) [m], at most
  /// dense_max_rounds rounds in all (<= dense_rounds: exactly dense_rounds rounds). Where only
  /// small objects pin a slide along large planes, each round moves the pose by millimetres to
  /// centimetres towards the truth: three rounds left four synthetic poses 2-5 cm off
  /// (docs/pipeline.md, "Converged dense rounds"). 16 since the extrapolation: on the synthetic
  /// sets 5 of 472 claimed poses reach it, against 16 of 469 with 8 plain rounds ("Extrapolated
  /// rounds").
  int dense_max_rounds = 16;
  double dense_converged_m = 0.002;
  /// After two rounds at the last gate that move the pose the same way, the next round starts
  /// ahead along the last step by the rest of the geometric series the two steps suggest, at
  /// most this many steps (step_extrapolation.h; Besl & McKay's accelerated ICP). 0 = off.
  /// A creeping synthetic pose that eight plain rounds leave 8 cm off comes within 1 cm in as
  /// many rounds (docs/pipeline.md, "Extrapolated rounds").
  double dense_extrapolation_max = 4.0;
  /// Line search at the last gate (truncated_score.h): a round whose step is longer than the
  /// round before must not lower the truncated point-to-plane score -- of the pose against the
  /// terms gathered where the step lands, compared with the pose it leaves against its own
  /// terms. Otherwise the step is halved, at most dense_line_search_halvings times, and when
  /// every length scores worse the rounds end at the last round's refined pose. A rolled cabinet
  /// pair whose rounds swung 2-8 cm about the reference for 16 rounds converges in 15 to where
  /// the upright pair ends; synthetic room RMSE 5.6 -> 5.1 mm, the sparse scene's worst pose
  /// 3.1 -> 0.4 cm; cabinet skip 1 1.19 -> 1.15 cm (docs/pipeline.md, "Line search at the last
  /// gate").
  bool dense_line_search = true;
  int dense_line_search_halvings = 3;  ///< >= 0; 0: a worse step ends the rounds at once
  ProjectiveTermParams projective;  ///< pixel step 8, normals within 20 deg
  /// Point-to-line terms along occluding edges in the dense rounds (edge_terms.h), gated like the
  /// pixel terms (edges.max_distance_m is replaced by the round's gate).
  bool edge_terms = true;
  EdgeTermParams edges;
  /// With edge terms: when fewer than wide_edge_min_paired_share of the source edge points that
  /// land on the target's depth have a target edge within the last gate at the refined pose (or
  /// when that refinement failed), a second refinement from the same
  /// patch pose runs with edge gates wide_edge_gate_factor (>= 1) times the pixel gates (0 = never),
  /// and the pose that passes the visibility check is kept; when both or neither pass, the one
  /// with the larger share of consistent samples. Slides
  /// larger than the pixel gates (the cabinet's 8 -> 10, 13 cm) leave the edges unpaired; wide
  /// edge gates alone pair wrong edges in clutter (fr1_xyz 620 -> 650 went 13 deg off), the
  /// selection keeps the right pose (docs/pipeline.md, "Edge terms").
  double wide_edge_gate_factor = 3.0;
  double wide_edge_min_paired_share = 0.6;  ///< in [0, 1]; slid cabinet pairs: 0-0.54
  /// Degeneracy rule of the dense problem. Its thousands of pixel terms are not independent, so
  /// its absolute standard deviations are optimistic and only the eigenvalue ratio separates a
  /// plane from a scene: a noisy single plane gives ~1e-4 (patch normals jitter by ~1 deg), a desk
  /// or a room corner above 3e-3 (docs/pipeline.md).
  DegeneracyParams dense_degeneracy{1e-3, 0.05};
  /// A claimed pose must rest on at least this many terms in its last dense round (pixel terms at
  /// projective.pixel_step 8 -- scale by (8 / step)^2 for another step -- plus edge terms): fewer
  /// say the pose puts too little surface of one view onto the other to be certified. Right poses
  /// of the benchmarks (fr1_xyz pairs from every 10th frame, fr3_cabinet_kf, the synthetic scenes
  /// with three noise seeds: 812 estimates) had at least 556 (fr1_xyz 430 -> 480, a small
  /// overlap); a look-alike alignment of the synthetic room 2.3 m / 90 deg off (noise seed 3,
  /// 39 -> 54, one-way partners, 5 % violations) had 100 (docs/pipeline.md). 0 = no limit.
  int min_dense_terms = 300;
  /// After the dense rounds, a claimed pose whose patch problem was degenerate is scanned for a
  /// slide along the unobservable directions and moved to where the views agree more
  /// (slide_scan.h): on the synthetic sparse scene five poses 5-21 cm / 1.1-3.4 deg off came to
  /// within 7 mm / 0.16 deg (docs/pipeline.md, "Slide scan").
  SlideScanParams slide_scan;
  /// Last: a pose whose mapped views contradict each other's free space is not claimed
  /// (look-alike structure, repeated objects).
  VisibilityCheckParams visibility;
  /// Finer-scale retry (0 = off; else in [0.01, 1)): when the views give no estimate and the
  /// failure is not a degenerate view or patch problem (pose.degenerate; a dense problem that is
  /// unobservable at RANSAC's pose is retried, PairResult::dense_unobservable), both depth images are
  /// segmented again with their own parameters (DepthView::superpixels) at this factor times
  /// their target_patch_area_m2, and the pair is registered once more with the mutual
  /// associations only and the one-way fallback's visibility limit (one_way_max_violation_ratio).
  /// Why: a small overlap holds too few patches of the default size for a consensus (fr1_xyz
  /// 440 -> 490, 540 -> 590: about 60 of 250-310 patches in the overlap); smaller patches give it
  /// more. 0.3 (12 cm^2 patches) is chosen on the fr1_xyz benchmark pairs (0.33 and 0.25 claim a
  /// poor pose there). One-way partners of small patches claimed a wrong pose (200 -> 250, 0.35 m /
  /// 23 deg), and look-alike synthetic boxes wrong poses with 12-23 % violations (right retry
  /// poses: at most 3.3 %), hence the two restrictions (docs/pipeline.md, "Finer-scale retry").
  /// Views without depth (depth_m empty) are not retried. The count thresholds
  /// (pose.ransac.min_inliers, min_guided_support) are not scaled: at 0.3 x the area they ask for
  /// less surface. PairResult::retry_views holds the views a retry's patch indices refer to.
  double retry_area_factor = 0.3;
  /// Added to the claimed pose's covariance for PairResult::edge_information (model_error.h):
  /// what the refinement's information leaves out. 1 cm and 0.75 deg per axis bring the median
  /// NEES of the real benchmark pairs (fr1_xyz, fr3_cabinet_kf, against their references) from
  /// 140-1080 times the chi-square median to 0.1-1.1 times it, with 82-100 % of the pairs within
  /// its 95 % quantile; on the simulator's pairs it is far too cautious (docs/pipeline.md, "How far
  /// the information can be trusted"). Changes no pose and no verdict.
  ModelError model_error;

  static AssociationParams defaultAssociation() {
    AssociationParams p;
    p.lambda = 0.7;
    return p;
  }
  static PoseEstimationParams defaultPoseParams() {
    PoseEstimationParams p;
    p.refinement.degeneracy.min_eigenvalue_ratio = 1e-3;
    return p;
  }
};

/// Throws gasp::Error naming the first invalid parameter.
void validate(const PairParams& params);

/// Wall-clock time per stage [ms] (segmentation is timed by the views themselves).
struct PairTimings {
  double association_ms = 0, ransac_ms = 0, refine_ms = 0, dense_ms = 0;
  double guided_ms = 0;  ///< guided verification (association under the pose hypotheses)
  double retry_segmentation_ms = 0;  ///< the finer-scale retry's segmentation of both views (0: no retry)
  double total() const {
    return association_ms + ransac_ms + refine_ms + dense_ms + guided_ms + retry_segmentation_ms;
  }
  /// Adds another attempt's stage times (all but retry_segmentation_ms).
  void addStages(const PairTimings& o) {
    association_ms += o.association_ms, ransac_ms += o.ransac_ms, refine_ms += o.refine_ms;
    dense_ms += o.dense_ms, guided_ms += o.guided_ms;
  }
};

struct PairResult {
  RegistrationResult pose;  ///< pose.success = an estimate is claimed; pose.reason otherwise
  /// For a pose graph: pose.information with PairParams::model_error added (model_error.h), in
  /// the same coordinates; zero when no pose is claimed. pose.information itself is the
  /// refinement's, on which the degeneracy verdicts rest.
  Matrix6d edge_information = Matrix6d::Zero();
  AssociationResult association;
  /// What RANSAC and the patch refinement ran on: one per entry of `used`, same order.
  std::vector<PatchCorrespondence> correspondences;
  /// The associations behind `correspondences`: association.associations, or with the one-way
  /// fallback those and association.one_way (used_one_way), or with guided_densify the guided ones.
  std::vector<PatchAssociation> used;
  bool used_one_way = false;  ///< the one-way fallback was needed
  /// Guided associations at the final pose (when one was claimed): the dense, verified patch
  /// associations of the pair (sorted by patch of the source).
  std::vector<PatchAssociation> verified;
  int guided_support = -1;  ///< guided associations at the verified pose (-1: stage not reached)
  int dense_terms = 0;  ///< dense terms in the last round
  int dense_rounds_run = 0;  ///< dense rounds solved for the final pose, a last one whose step the line search refused included (0: none)
  /// The dense rounds ended unobservable (pose.degenerate set by the dense refinement, not by the
  /// view check). The patch problem may have been degenerate as well: a degenerate patch pose with
  /// inliers goes on to the dense rounds, and their verdict is what counts. The finer-scale retry
  /// may still run (its own dense rounds judge again).
  bool dense_unobservable = false;
  /// RMS displacement of the source patches in the last dense round [m]; below
  /// PairParams::dense_converged_m the rounds converged (-1: no round succeeded).
  double dense_last_step_m = -1.0;
  int dense_steps_shortened = 0;  ///< steps the dense rounds' line search shortened (PairParams::dense_line_search)
  /// The line search ended the dense rounds: every length of the last step scored worse than the
  /// pose it left (dense_last_step_m is then 0, and the pose is the round before's).
  bool dense_line_search_stopped = false;
  VisibilityCheck visibility;  ///< of the final pose (when one was found)
  /// The visibility check refused a pose on its violation or occlusion limits
  /// (VisibilityCheck::free_space_refused), at the default scale or in the finer-scale retry:
  /// what a scene that changed between the views does (odometry's scene_change.h).
  bool visibility_refused = false;
  bool wide_edge_pose = false;  ///< the final pose came from the wide-edge-gate refinement
  /// Share of the source edge points on the target's depth with a target edge within the last gate at the first dense
  /// refinement's pose (-1: not measured -- no edge terms, no dense rounds or no pose).
  double edge_paired_share = -1.0;
  SlideScanReport slide;  ///< the slide scan of the claimed pose (slide.ran false: not needed)
  PairTimings timings;
  /// The finer-scale retry ran (PairParams::retry_area_factor): the default scale gave no estimate.
  bool retried = false;
  /// Set when the result is the retry's (it found the estimate): the re-segmented source and target
  /// views, to which association, used, correspondences and verified refer. Null: they refer to
  /// the views passed in; when the retry found nothing either, the result is the default scale's
  /// with both reasons. viewsOf() picks the right pair.
  std::shared_ptr<const std::pair<DepthView, DepthView>> retry_views;
};

/// The source and target views whose patches r's indices (association, used, verified) refer to:
/// r.retry_views when set, else the views passed to registerViews().
std::pair<const DepthView*, const DepthView*> viewsOf(const PairResult& r, const DepthView& source,
                                                      const DepthView& target);

/// The pieces of the finer-scale retry (PairParams::retry_area_factor), for callers that register
/// many view pairs and want each view re-segmented once (CGaspAligner): `view` segmented again with
/// its own parameters (DepthView::superpixels) at area_factor times their target area (throws
/// gasp::Error for a view whose depth does not match its intrinsics), and the parameters the
/// retry registers with (no further retry, no one-way fallback, and the one-way fallback's
/// stricter visibility limit, one_way_max_violation_ratio).
DepthView finerScaleView(const DepthView& view, double area_factor);
PairParams finerScaleParams(const PairParams& params);
/// Whether a default-scale result `r` of source -> target is one the retry may still turn into
/// an estimate: no pose, no degenerate view or patch problem (a dense problem unobservable at
/// RANSAC's pose does not stop it: r.dense_unobservable), depth in both views.
bool finerScaleRetryApplies(const PairResult& r, const DepthView& source, const DepthView& target);
/// "at 0.3x the patch area: " + reason: how a retry's outcome is named in reasons.
std::string finerScaleReason(double area_factor, const std::string& reason);

/// Registers `source` (view A) to `target` (view B): pose.T_target_source maps A's camera frame
/// into B's. Never throws for data (empty views, NaN, no overlap give pose.success = false with
/// pose.reason); throws gasp::Error for invalid parameters.
PairResult registerViews(const DepthView& source, const DepthView& target, const PairParams& params = {});

}  // namespace gasp
