#pragma once
/// \file certify_stage.h Stage 5 of the pair pipeline: whether a full pose, a partial pose or no
/// estimate is claimed, and with which information.
///
/// The rule: a direction of the pose is observed when both views' patch geometry
/// (view_degeneracy.h) and the dense problem's information (the refine stage's solver,
/// degeneracy.h) constrain it; a pose resting on enough dense terms that passes the free-space
/// test (visibility_check.h) is full when every direction is observed, partial when at most three
/// are not (partial_pose.h: one plane fixes three) and the views' own geometry leaves some
/// direction free (where both views fix every direction and the pose's terms do not, the
/// structure that fixes them was not brought into alignment), and no estimate otherwise. A partial pose's
/// information is zero in exactly its free directions. Where the views' own geometry leaves
/// directions free, a partial pose rests on the alignment of their dominant plane, which is unique
/// only when no other large parallel plane could be matched instead (plane_hypothesis.h: a floor
/// under a table top): otherwise no estimate. A claimed pose's information for pose
/// graphs adds the model error (model_error.h) to the refinement's, in its observed directions.
/// With partial_poses off, a view that cannot fix a pose gives no estimate before association,
/// and so does a pose with any unobservable direction.
///
/// Uniqueness: a claimed pose must explain the views at least min_likelihood_ratio times better
/// (pose_likelihood.h), and by kUniquenessStandardErrors standard errors of the ratio, than the
/// best distinct alternative RANSAC found, passing the guided verification, refined by the
/// dense rounds from RANSAC's pose (no patch refinement, so no slide scan for a full pose) and
/// claimed by the rule above; where the alternative explains them that much better it is taken
/// instead, and otherwise there is no estimate ("not unique"). Distinct: the two poses place the
/// source patches' centroids more than twice RANSAC's inlier distance apart (RMS), in the chosen
/// pose's observed directions: they cannot both lie within it of the truth.
#include <limits>
#include <optional>
#include <string>

#include <Eigen/Core>

#include "gasp/pipeline/depth_view.h"
#include "gasp/pipeline/model_error.h"
#include "gasp/pipeline/plane_hypothesis.h"
#include "gasp/pipeline/pose_likelihood.h"
#include "gasp/pipeline/view_degeneracy.h"
#include "gasp/pipeline/visibility_check.h"
#include "gasp/registration/registration_result.h"

namespace gasp {

struct CertifyParams {
  ViewDegeneracyParams view_degeneracy;  ///< eigenvalue ratio 1e-3 of a view's patch planes
  /// Claim partial poses (the file's comment); off: only full poses.
  bool partial_poses = true;
  /// A claimed pose rests on at least this many terms in its last dense round (pixel terms at the
  /// refine stage's pixel step 8 -- scale by (8 / step)^2 for another step -- plus edge terms):
  /// fewer say it puts too little surface of one view onto the other. 0 = no limit.
  int min_dense_terms = 300;
  /// The free-space test: gate 3 cm + 2 cm/m^2 z^2, at most 15 % violations (5 % seen from both
  /// views), at most 50 % occluded, at least 50 consistent samples.
  VisibilityCheckParams visibility;
  /// The violation limit for a pose from a fallback hypothesis set (one-way partners, the
  /// finer-scale retry; retry_stage.h): the lower of this and visibility.max_violation_ratio.
  /// Wider hypothesis sets hold more look-alike alignments, so their poses must explain the views
  /// better.
  double fallback_max_violation_ratio = 0.08;
  /// Added to a claimed pose's covariance for PairResult::edge_information: 1 cm and 0.75 deg per
  /// axis, what the refinement's information leaves out (model_error.h).
  ModelError model_error;
  /// Uniqueness (above): the likelihood ratio a claimed pose needs over a distinct alternative;
  /// 1000 is about two patches' worth of surface explained (pose_likelihood.h). 0 = not tested.
  double min_likelihood_ratio = 1000.0;
  /// What the likelihood comparisons (uniqueness, symmetry) charge a sample in the other view's
  /// free space beyond an outlier [nats, >= 0] (pose_likelihood.h: only a random reading explains
  /// it; the free-space test's gate tells it). 0: violations count as outliers, as occluded samples
  /// do (a camera's default, measured so). LiDAR sweeps: ln 10 (LidarParams::violation_nats).
  double violation_nats = 0.0;
  /// Symmetry: a claimed full pose is not claimed (no estimate) when one of its symmetric turns
  /// (symmetric_turns.h), refined by the dense rounds, explains the views better (a higher
  /// likelihood, pose_likelihood.h) -- a box-shaped scene turned onto itself. Off for a camera
  /// (not measured there); on for LiDAR sweeps (LidarParams::symmetry_test), whose all-round
  /// views of a near-square room match it turned a quarter (docs/lidar.md "The symmetry test").
  bool symmetry_test = false;
};

/// Throws gasp::Error naming the first invalid parameter.
void validate(const CertifyParams& params);

/// What each view's geometry leaves free.
struct ViewsCertificate {
  /// The no-estimate verdict (degenerate, its eigenvalues, unobservable directions and the reason
  /// naming the view) when a view cannot fix a pose -- with partial_poses, only when it leaves
  /// more than three directions free; nullopt: go on.
  std::optional<RegistrationResult> refusal;
  /// The directions each view leaves free, as left perturbations [t r] of its own camera frame
  /// (DegeneracyAnalysis::unobservable_twists); no columns when it fixes a pose.
  Eigen::Matrix<double, 6, Eigen::Dynamic> source_free, target_free;
  /// Each view's dominant plane (plane_hypothesis.h), found once per pair where a partial pose
  /// can rest on it: with partial_poses, when a view leaves directions free.
  std::optional<DominantPlane> source_plane, target_plane;
};
ViewsCertificate certifyViews(const DepthView& source, const DepthView& target, const CertifyParams& params);

/// The free-space test's parameters for a pose; `fallback`: from a fallback hypothesis set
/// (fallback_max_violation_ratio applies).
VisibilityCheckParams visibilityLimits(const CertifyParams& params, bool fallback);

/// The free-space test a pose from this pair faces; `fallback`: the pose came from a fallback
/// hypothesis set (fallback_max_violation_ratio applies).
FreeSpaceTest freeSpaceTest(const DepthView& source, const DepthView& target, const CertifyParams& params,
                            bool fallback);

struct Certificate {
  bool claimed = false;         ///< a full or a partial pose
  bool partial = false;         ///< claimed in the observed directions only
  /// Partial: the free directions, an orthonormal basis in the pose's conditioned coordinates
  /// (RegistrationResult::unobservable_directions), the views' and the dense problem's together.
  Eigen::Matrix<double, 6, Eigen::Dynamic> free_directions;
  std::string reason;           ///< why not claimed; for a partial pose, which directions are free
  std::optional<VisibilityCheck> visibility;  ///< the free-space test of the pose (when it ran)
  bool free_space_refused = false;  ///< refused on the free-space test's violation or occlusion limits
  /// Refused because the pose's terms leave free a direction both views' own geometry fixes (the
  /// structure that fixes it was not brought into alignment). For LiDAR views, the returns may
  /// fix it (pair_registration.h, stage 7).
  bool not_aligned = false;
  /// Claimed only: information with the model error, zero in a partial pose's free directions.
  Matrix6d edge_information = Matrix6d::Zero();
};

/// The verdict on `pose` (pose.estimated(): the refinement gives a full or partial pose).
/// `dense_terms`: terms of the last dense round (nullopt: no dense refinement ran, no limit);
/// `done`: the free-space test of this pose, when already run; `views`: certifyViews() of the pair.
Certificate certify(const RegistrationResult& pose, std::optional<int> dense_terms, const FreeSpaceTest& free_space,
                    const std::optional<VisibilityCheck>& done, const ViewsCertificate& views,
                    const CertifyParams& params);

/// Standard errors of the log-likelihood ratio (pose_likelihood.h) a pose needs over a distinct
/// alternative: less is what the sensor's noise gives between poses the surfaces cannot tell apart.
constexpr double kUniquenessStandardErrors = 3.0;

/// The uniqueness test of a claimed pose against a distinct alternative (above).
struct Uniqueness {
  bool tested = false;  ///< the alternative was claimed and distinct, and some sample lands under both
  /// log L(chosen) - log L(alternative) (pose_likelihood.h); NaN when not tested.
  double log_ratio = std::numeric_limits<double>::quiet_NaN();
  double standard_error = 0.0;  ///< of log_ratio
  double distance_m = 0.0;   ///< RMS displacement of the source centroids between the two, observed directions
  bool take_alternative = false;  ///< the alternative explains the views min_likelihood_ratio times better
  bool refused = false;           ///< neither is min_likelihood_ratio times more likely: no estimate
  std::string reason;             ///< when refused
};

/// `chosen` and `alternative` are claimed poses of the same views (certify()); `distinct_m`:
/// twice RANSAC's inlier distance. Not tested when the ratio is 0 or the two are not distinct.
Uniqueness compareAlternative(const DepthView& source, const DepthView& target, const RegistrationResult& chosen,
                              const RegistrationResult& alternative, double distinct_m, const CertifyParams& params);
/// The chosen pose's samples of the uniqueness test's likelihood, for comparing it with many
/// alternatives (the symmetry test's turns) at the cost of one pose each; none (only the pose)
/// when the test is off (min_likelihood_ratio 0).
PoseSamples samplesForComparison(const DepthView& source, const DepthView& target, const RegistrationResult& chosen,
                                 const CertifyParams& params);
/// compareAlternative() with the chosen pose's samples from `chosen_samples` (samplesForComparison
/// of the same views, pose and params; throws gasp::Error when they are of another pose): the
/// same verdict to the bit.
Uniqueness compareAlternative(const DepthView& source, const DepthView& target, const RegistrationResult& chosen,
                              const RegistrationResult& alternative, double distinct_m, const CertifyParams& params,
                              const PoseSamples& chosen_samples);
/// The same on two sweeps' own returns (returnsLogLikelihoodRatio, pose_likelihood.h; both views
/// carry DepthView::returns, else not tested): where binned cells, means of different returns in
/// each sweep, cannot tell the two poses apart fairly, the returns can.
Uniqueness compareAlternativeOnReturns(const DepthView& source, const DepthView& target, const RegistrationResult& chosen,
                                       const RegistrationResult& alternative, double distinct_m,
                                       const CertifyParams& params, double range_sigma_m, double max_incidence_deg);

}  // namespace gasp
