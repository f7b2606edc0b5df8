#pragma once
/// \file method_run.h gasp-pairs: one method on one pair. GASP's pipeline (gasp, gasp-norefine,
/// gasp-gicp: then PCL's GICP from its pose), PCL's GICP from the identity (gicp) and the feature
/// baselines (fpfh, shot, cshot, sift, dsift) when the build has them; each pose must pass the
/// same visibility check. With ground truth, GASP's runs also score their associations.
#include <opencv2/core.hpp>

#include <cstddef>
#include <map>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "frame_cache.h"
#include "gasp/association/association_quality.h"
#include "gasp/core/pose.h"
#include "gasp/eval/pose_consistency.h"
#include "gasp/pipeline/pair_registration.h"
#include "gasp/registration/partial_pose.h"
#ifdef GASP_HAVE_BASELINES
#include "gasp/baselines/baseline_registration.h"
#endif

namespace gasp::pairs {

/// Every method this build can run, in --help's order.
std::vector<std::string> knownMethods();
/// GASP's pipeline runs (gasp-gicp: then PCL's GICP from its pose).
bool isGasp(const std::string& method);
/// Methods that need the colour images.
bool needsColour(const std::string& method);

/// One pair, one method: the outcome plus what the pairs CSV and the pictures need.
struct MethodRun {
  bool estimated = false;  ///< a full pose
  Isometry3 T_target_source = Isometry3::Identity();
  /// GASP: a partial pose (certify_stage.h; estimated is then false), its number of free
  /// directions and, with ground truth, its error in the observed directions (partial_pose.h).
  bool partial = false;
  int free_directions = 0;
  std::optional<ObservedError> observed;
  /// GASP: the certificate's uniqueness test (PairResult::uniqueness_log_ratio; NaN: not tested)
  /// and whether RANSAC's alternative replaced the pose.
  double uniqueness_log_ratio = std::numeric_limits<double>::quiet_NaN();
  bool alternative_taken = false;
  std::string reason;
  double ms = 0;
  std::size_t associations = 0;
  int inliers = 0;
  double violation_ratio = 0;
  double violation_ratio_lesser = 0;  ///< visibility check, the other direction
  double violation_blob_share_lesser = 1, violation_blob_share = 1;  ///< VisibilityCheck's, both directions
  int consistent = 0, occluded = 0, violations = 0;  ///< visibility check samples, both directions
  double occluded_ratio = 0;                          ///< visibility check, the worse direction
  int one_way = 0;          ///< GASP: the pose came from the one-way fallback
  int guided_support = -1;  ///< GASP: guided associations under the pose (-1: not reached)
  bool finer_scale = false; ///< GASP: the estimate came from the finer-scale retry
  bool slide_moved = false; ///< GASP: the slide scan moved the pose (slide_scan.h)
  int dense_terms = 0;      ///< GASP: terms of the last dense round (0: no dense rounds ran)
  int dense_rounds = 0;     ///< GASP: dense rounds run for the final pose (0: none)
  double dense_last_step_m = -1.0;  ///< GASP: RMS motion of the source patches in the last dense round (-1: none)
  int dense_shortened = 0;  ///< GASP: dense steps the line search shortened
  bool dense_stopped = false;  ///< GASP: the line search ended the dense rounds
  /// GASP with an estimate and ground truth: the error's NEES under the edge information (PairResult)
  /// and its translation and rotation parts (pose_consistency.h; chi-square with 6, 3 and 3
  /// degrees of freedom if the information were right).
  std::optional<eval::NeesParts> nees;
  std::optional<double> nees_refinement;  ///< the same under the refinement's own information
  /// GASP with ground truth: free and verified associations scored (association_quality.h).
  std::optional<AssociationQuality> free_quality, verified_quality;
  /// The verified associations scored against the GICP-polished reference (--polish-reference).
  std::optional<AssociationQuality> verified_quality_polished;
  /// GASP with ground truth: how well each pose explains the depth (depthAgreement, every 4th pixel), the estimate's
  /// and the ground truth's, so a disagreement between them can be told apart.
  std::optional<double> agreement_estimate, agreement_truth;
  std::map<std::string, double> stage_ms;
};

/// The picture of one method on one pair: GASP's association picture (patches in shared
/// colours), or the baselines' keypoint matches over the rgb images. Lines are green where the
/// ground truth says correct (GASP: the same surface, association_quality.h; keypoints: the
/// mapped source keypoint within 5 cm of its partner), red where wrong.
struct Picture {
  cv::Mat image;
  std::size_t shown = 0, correct = 0;
};

/// What every run shares: the parameters and the target's roll.
struct MethodSetup {
  PairParams gasp;        ///< GASP's parameters (gasp-norefine: with refine off)
  int roll_target_deg = 0;  ///< GASP's methods: the target view turned clockwise (camera_roll.h)
  /// GASP's pictures: the free associations (before any pose) instead of the verified ones.
  bool picture_free = false;
#ifdef GASP_HAVE_BASELINES
  baselines::BaselineParams baseline;
#endif
};

/// Runs `method` on the pair (i -> j): i is the source, j the target. `picture`: also drawn;
/// `T_gt`: scores the associations; `T_ref_icp`: the verified associations also against it.
MethodRun runMethod(const std::string& method, std::size_t i, std::size_t j, FrameCache& cache,
                    const MethodSetup& setup, Picture* picture, const std::optional<Isometry3>& T_gt,
                    const std::optional<Isometry3>& T_ref_icp = std::nullopt);

/// PCL's GICP from T_init between the views GASP registers (undistorted where the intrinsics have
/// distortion; the cached depth); none without the baselines or when it fails.
std::optional<Isometry3> polishWithGicp(FrameCache& cache, std::size_t i, std::size_t j,
                                        const SuperpixelParams& params, const Isometry3& T_init);

}  // namespace gasp::pairs
