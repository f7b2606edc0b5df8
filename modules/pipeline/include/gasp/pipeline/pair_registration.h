#pragma once
/// \file pair_registration.h The GASP front-end for one pair of depth views, as the paper's chain
/// of stages, each in its own file with its own parameters and verdict:
///   1. segment      depth image -> regularised surface patches (depth_view.h, superpixels module)
///   2. associate    invariant neighbourhood feature sets, restricted Damerau-Levenshtein matching
///                   (associate_stage.h)
///   3. hypothesise  RANSAC over the associated centroids, patch point-to-plane refinement, guided
///                   verification (hypothesise_stage.h); for views that leave directions free and
///                   give no hypothesis, their dominant planes aligned (plane_hypothesis.h); for
///                   two sweeps whose association gives no claimed pose, the ground search
///                   (ground_search.h)
///   4. refine       dense point-to-plane and edge rounds (refine_stage.h)
///   5. certify      observability, dense support, free space; the information (certify_stage.h)
///   6. retry        one-way partners, then a finer scale, when the chain gives no estimate
///                   (retry_stage.h)
///   7. returns      LiDAR views: point-to-plane rounds on the sweeps' own returns from a
///                   claimed pose (returns_stage.h); from a pose refused for a direction the
///                   cells leave free that the views fix, or on the cells' free-space test,
///                   when the returns fix it (their basin) and their pose passes the
///                   certificate (after a free-space refusal, its test on the returns); in
///                   registerViews and registerViewSets a claimed pose's returns' pose must be
///                   the likeliest of the minima their restarts find (no estimate otherwise)
/// The result is what a SLAM system consumes: T_target_source with its information matrix, or
/// no estimate with the reason (too few associations, no consensus, degenerate geometry,
/// contradicted free space).
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "gasp/pipeline/associate_stage.h"
#include "gasp/pipeline/certify_stage.h"
#include "gasp/pipeline/depth_view.h"
#include "gasp/pipeline/ground_search.h"
#include "gasp/pipeline/hypothesise_stage.h"
#include "gasp/pipeline/refine_stage.h"
#include "gasp/pipeline/retry_stage.h"
#include "gasp/pipeline/returns_stage.h"
#include "gasp/pipeline/sweep_motion.h"

namespace gasp {

/// One params struct per stage, and nothing else.
struct PairParams {
  /// Stage 1, for the callers that make the views (makeDepthView(), registerDepthImages()).
  /// registerViews() takes views already segmented; its finer-scale retry segments each view again
  /// with the parameters it was made with (DepthView::superpixels).
  SuperpixelParams segment;
  AssociationParams associate = defaultAssociateParams();
  HypothesiseParams hypothesise;
  RefineParams refine;
  CertifyParams certify;
  RetryParams retry;
  /// Stage 7: runs only when both views carry their sweep's returns (DepthView::returns).
  ReturnsRefineParams returns;
  /// The hypothesis for sweeps whose association gives no claimed pose: runs only when both views
  /// carry their returns (ground_search.h).
  GroundSearchParams ground_search;
  /// Stage 8: runs only for two views of sweeps whose columns carry their times (sweep_motion.h).
  SweepMotionParams sweep_motion;
};

/// Throws gasp::Error naming the stage and the first invalid parameter.
void validate(const PairParams& params);

/// Wall-clock time per stage [ms] (segmentation is timed by the views themselves).
struct PairTimings {
  double association_ms = 0, ransac_ms = 0, refine_ms = 0, dense_ms = 0;
  double guided_ms = 0;    ///< guided verification (association under the pose hypotheses)
  double certify_ms = 0;   ///< the certificate: its free-space test, and the uniqueness test (the alternative's refinement included)
  double retry_segmentation_ms = 0;  ///< the finer-scale retry's segmentation of both views (0: no retry)
  double returns_ms = 0;   ///< stage 7, the returns' rounds (LiDAR views)
  double ground_search_ms = 0;  ///< the ground search (LiDAR views association gave no claimed pose for)
  /// Stage 8: the test at rest, the sweeps' motion estimated, and for moving sweeps their deskew
  /// and segmentation (the second registration's stages are added to the others).
  double sweep_motion_ms = 0;
  double total() const {
    return association_ms + ransac_ms + refine_ms + dense_ms + guided_ms + certify_ms + retry_segmentation_ms +
           returns_ms + ground_search_ms + sweep_motion_ms;
  }
  /// Adds another attempt's stage times (all but retry_segmentation_ms).
  void addStages(const PairTimings& o) {
    association_ms += o.association_ms, ransac_ms += o.ransac_ms, refine_ms += o.refine_ms;
    dense_ms += o.dense_ms, guided_ms += o.guided_ms, certify_ms += o.certify_ms, returns_ms += o.returns_ms;
    ground_search_ms += o.ground_search_ms, sweep_motion_ms += o.sweep_motion_ms;
  }
};

struct PairResult {
  /// pose.success: a full pose is claimed; pose.partial: a partial one (certify_stage.h), free
  /// along pose.unobservable_directions (partial_pose.h); neither: no estimate, pose.reason says why.
  RegistrationResult pose;
  /// For a pose graph: pose.information with CertifyParams::model_error added (model_error.h), in
  /// the same coordinates, zero in a partial pose's free directions; zero when no pose is
  /// claimed. pose.information itself is the refinement's, on which the degeneracy verdicts rest.
  Matrix6d edge_information = Matrix6d::Zero();
  /// Directions the views' own patch geometry leaves free, counted over both views
  /// (certifyViews(); 0: each view can fix a pose).
  int views_free_directions = 0;
  /// Association gave no hypothesis and the views leave directions free: the dense rounds started
  /// from the views' dominant planes aligned (plane_hypothesis.h; partial poses only).
  bool plane_hypothesis = false;
  /// Association gave no claimed pose for two sweeps, and the claimed pose is the ground search's:
  /// the dense rounds started from its best pose (ground_search.h), and its distinct runner-up was
  /// judged as RANSAC's alternative is (the uniqueness test). When the search's pose is refused too,
  /// the result is association's with both reasons, timings.ground_search_ms set, and this unset.
  bool ground_search = false;
  AssociationResult association;
  /// What the hypothesis stage ran on: one per entry of `used`, same order.
  std::vector<PatchCorrespondence> correspondences;
  /// The associations behind `correspondences`: association.associations, or with the one-way
  /// fallback those and association.one_way (used_one_way), or with guided densify the guided ones.
  std::vector<PatchAssociation> used;
  bool used_one_way = false;  ///< the one-way fallback was needed
  /// Guided associations at the final pose (when one was claimed): the dense, verified patch
  /// associations of the pair (sorted by patch of the source).
  std::vector<PatchAssociation> verified;
  int guided_support = -1;  ///< guided associations at the last hypothesis verified (-1: stage not reached)
  int dense_terms = 0;  ///< dense terms in the last round
  int dense_rounds_run = 0;  ///< dense rounds solved for the final pose, a last one whose step the line search refused included (0: none)
  /// The dense rounds ended unobservable (pose.degenerate set by the dense refinement, not by the
  /// view check). The patch problem may have been degenerate as well: a degenerate patch pose with
  /// inliers goes on to the dense rounds, and their verdict is what counts. The finer-scale retry
  /// may still run (its own dense rounds judge again).
  bool dense_unobservable = false;
  /// RMS displacement of the source patches in the last dense round [m]; below
  /// the refine stage's converged_m the rounds converged (-1: no round succeeded).
  double dense_last_step_m = -1.0;
  int dense_steps_shortened = 0;  ///< steps the dense rounds' line search shortened
  /// The line search ended the dense rounds: every length of the last step scored worse than the
  /// pose it left (dense_last_step_m is then 0, and the pose is the round before's).
  bool dense_line_search_stopped = false;
  VisibilityCheck visibility;  ///< the free-space test of the final pose (when one was found)
  /// The free-space test refused a pose on its violation or occlusion limits
  /// (VisibilityCheck::free_space_refused), at the default scale or in the finer-scale retry:
  /// what a scene that changed between the views does (odometry's scene_change.h).
  bool visibility_refused = false;
  bool wide_edge_pose = false;  ///< the final pose came from the wide-edge-gate refinement
  /// Share of the source edge points on the target's depth with a target edge within the last gate
  /// at the first dense refinement's pose (-1: not measured -- no edge terms, no dense rounds or no pose).
  double edge_paired_share = -1.0;
  SlideScanReport slide;  ///< the slide scan of the claimed pose (slide.ran false: not needed)
  /// The certificate's uniqueness test (certify_stage.h): log L(claimed) - log L(the best distinct
  /// alternative RANSAC found, refined and claimed), or for a refused pose the ratio that refused
  /// it; NaN when there was no such alternative (not tested).
  double uniqueness_log_ratio = std::numeric_limits<double>::quiet_NaN();
  /// The alternative explained the views min_likelihood_ratio times better and replaced the pose.
  bool alternative_taken = false;
  PairTimings timings;
  /// The finer-scale retry ran (RetryParams::finer_area_factor): the default scale gave no estimate.
  bool retried = false;
  /// The estimate is the finer-scale retry's (its patches, not the default decomposition's).
  bool finer_scale = false;
  /// Set when the result is the retry's (it found the estimate) or the deskewed sweeps' (stage 8):
  /// the re-made source and target views, to which association, used, correspondences and verified
  /// refer. Null: they refer to
  /// the views passed in; when the retry found nothing either, the result is the default scale's
  /// with both reasons. viewsOf() picks the right pair.
  std::shared_ptr<const std::pair<DepthView, DepthView>> retry_views;
  /// Stage 7 (LiDAR views): the returns' rounds refined the claimed pose, whose pose.T_target_source,
  /// pose.information and edge_information are then theirs (the other fields -- inliers, dense
  /// terms, and visibility unless returns_fixed_free -- describe the cells' pose). When they ran
  /// and failed, the cells' pose stays and returns_reason says why. In registerViews and
  /// registerViewSets a restart of theirs may find a likelier minimum (docs/lidar.md "A claimed
  /// pose's basin"): better by the uniqueness test's margin, it becomes the pose; better by less,
  /// there is no estimate: pose.success is false, edge_information zero, verified empty, and
  /// returns_reason and pose.reason say why.
  bool returns_refined = false;
  std::string returns_reason;
  /// Stage 7 answered the cells' refusal: the certificate refused the cells' pose for a direction
  /// their terms leave free while both views' geometry fixes it (Certificate::not_aligned) or, in
  /// registerViews, on its free-space test; the returns' rounds from it fixed every direction, held
  /// their basin (returnsBasin) and passed the certificate (visibility is its free-space test, on
  /// the returns after a free-space refusal: returnsFreeSpace); the claimed pose is theirs
  /// (returns_refined), and cells_reason keeps the refusal. When the uniqueness or symmetry test then refuses their
  /// pose, the cells' refused pose is restored, both reasons in pose.reason, and these are unset.
  bool returns_fixed_free = false;
  std::string cells_reason;
  /// Stage 8 (two timed sweeps, registerViews): the test at rest at the claimed pose and, when it
  /// rejects rest, the sweeps' own motions estimated from it. When sweep_motion.moving, both
  /// sweeps were deskewed with their twists and registered again, and the rest of this result is
  /// that registration's, of the deskewed sweeps' views (retry_views holds them). Otherwise the
  /// result is the sweeps' as they were read, and sweep_motion.reason says why (at rest, or not
  /// estimated); at rest but not sweep_motion.determined, the pose is no estimate, with that
  /// reason.
  SweepMotion sweep_motion;
};

/// The source and target views whose patches r's indices (association, used, verified) refer to:
/// r.retry_views when set (the finer-scale retry's or the deskewed sweeps' views), else the views
/// passed to registerViews().
std::pair<const DepthView*, const DepthView*> viewsOf(const PairResult& r, const DepthView& source,
                                                      const DepthView& target);

/// Registers `source` (view A) to `target` (view B): pose.T_target_source maps A's camera frame
/// into B's. Never throws for data (empty views, NaN, no overlap give pose.success = false with
/// pose.reason); throws gasp::Error for invalid parameters.
PairResult registerViews(const DepthView& source, const DepthView& target, const PairParams& params);
/// With the default parameters.
PairResult registerViews(const DepthView& source, const DepthView& target);

/// The tracking path of a sequence (odometry.h): registers `source` to `target` from a predicted
/// pose with the cheap stages only -- the view check, the refine stage's dense rounds started at
/// T_target_source_predicted (no association, RANSAC or patch inliers; no finer-scale retry) and
/// the certificate; for LiDAR views, then the returns' rounds on a claimed pose (stage 7, which
/// costs about as much as the dense rounds: every return of the source). Association is what makes GASP independent of a start; given a good one the
/// dense rounds alone reach the same pose, and the certificate says when they did not (a caller
/// then runs registerViews()). The result's association, correspondences and verified sets are
/// empty. The dense rounds are anchored by the patch pairs RANSAC would count as inliers at the
/// prediction (projectivePatchPairs(), projective_terms.h); no patch refinement runs first, so
/// the slide scan (slide_scan.h) runs for a partial pose only. `target_edges`: the target's edge
/// targets when built before (refine(); e.g. a keyframe's, once for all the frames tracked
/// against it). Never throws for data; throws gasp::Error for invalid parameters.
PairResult trackViews(const DepthView& source, const DepthView& target, const Isometry3& T_target_source_predicted,
                      const PairParams& params, const EdgeTargets* target_edges = nullptr);

/// Stage 1 and the rest: both depth images segmented with params.segment (concurrently), then
/// registerViews(). Throws gasp::Error for a depth image that does not match the intrinsics.
PairResult registerDepthImages(const cv::Mat& source_depth_m, const cv::Mat& target_depth_m,
                               const CameraIntrinsics& intrinsics, const PairParams& params = {});

/// Many views against many (a map of several views against another, CGaspAligner): every source
/// view is registered to every target view at the views' own scale; only when none gives an
/// estimate does the finer-scale retry run, on the pairs where it applies, with each view
/// segmented again once (not once per pair).
struct ViewSetRegistration {
  std::size_t source = 0, target = 0;  ///< indices into the sources and targets
  PairResult result;
  /// From the finer-scale retry: result's patch indices refer to the views segmented again, which
  /// are not kept (result.retry_views is null); a failure's reason says so.
  bool finer_scale = false;
};
struct ViewSetResult {
  std::vector<ViewSetRegistration> registrations;  ///< every registration run, in order
  /// The one to use: the full pose at the views' own scale with the most inliers, else the
  /// finer-scale one with the most inliers; without any, a partial pose (most inliers); else the
  /// failure with the most inliers (its reason is the informative one). -1: nothing was registered.
  int best = -1;
  /// Views whose finer-scale segmentation failed ("source view 2: ..."); their pairs are not retried.
  std::vector<std::string> notes;
};
/// Stage 7 (LiDAR views) runs on the registration chosen as `best`; when the claimed pose's basin
/// refuses it (heldBasin, docs/lidar.md "A claimed pose's basin"), on the next best, which becomes
/// `best`. Throws gasp::Error for
/// invalid parameters or a null view pointer; never for data.
ViewSetResult registerViewSets(const std::vector<const DepthView*>& sources,
                               const std::vector<const DepthView*>& targets, const PairParams& params = {});

}  // namespace gasp
