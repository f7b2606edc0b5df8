#pragma once
/// \file certify_stage.h Stage 5 of the pair pipeline: whether a pose is claimed, and with which
/// information. Before association, each view's own geometry must be able to fix a pose
/// (view_degeneracy.h: one plane, parallel planes cannot). After refinement, a pose is claimed
/// when its dense problem was observable (the refine stage's solver verdict), rests on enough
/// dense terms, and passes the free-space test (visibility_check.h: the mapped views must not
/// contradict each other's free space, as look-alike structure and repeated objects do). A
/// claimed pose's information for pose graphs adds the model error (model_error.h) to the
/// refinement's.
#include <optional>
#include <string>

#include "gasp/pipeline/depth_view.h"
#include "gasp/pipeline/model_error.h"
#include "gasp/pipeline/view_degeneracy.h"
#include "gasp/pipeline/visibility_check.h"
#include "gasp/registration/registration_result.h"

namespace gasp {

struct CertifyParams {
  ViewDegeneracyParams view_degeneracy;  ///< eigenvalue ratio 1e-3 of a view's patch planes
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
};

/// Throws gasp::Error naming the first invalid parameter.
void validate(const CertifyParams& params);

/// Whether each view's geometry can fix a pose: nullopt when both can; else the no-estimate
/// verdict (degenerate, its eigenvalues, unobservable directions and the reason naming the view).
std::optional<RegistrationResult> certifyViews(const DepthView& source, const DepthView& target,
                                               const CertifyParams& params);

/// The free-space test a pose from this pair faces; `fallback`: the pose came from a fallback
/// hypothesis set (fallback_max_violation_ratio applies).
FreeSpaceTest freeSpaceTest(const DepthView& source, const DepthView& target, const CertifyParams& params,
                            bool fallback);

struct Certificate {
  bool claimed = false;
  std::string reason;           ///< why not claimed
  std::optional<VisibilityCheck> visibility;  ///< the free-space test of the pose (when it ran)
  bool free_space_refused = false;  ///< refused on the free-space test's violation or occlusion limits
  Matrix6d edge_information = Matrix6d::Zero();  ///< claimed only: information with the model error
};

/// The verdict on `pose` (pose.success: the refinement claims it). `dense_terms`: terms of the
/// last dense round (nullopt: no dense refinement ran, no limit); `done`: the free-space test of
/// this pose, when already run.
Certificate certify(const RegistrationResult& pose, std::optional<int> dense_terms, const FreeSpaceTest& free_space,
                    const std::optional<VisibilityCheck>& done, const CertifyParams& params);

}  // namespace gasp
