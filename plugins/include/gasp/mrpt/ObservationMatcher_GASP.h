#pragma once
/// \file ObservationMatcher_GASP.h GASP's pair pipeline (gasp/pipeline/pair_registration.h) as an
/// ObservationMatcher for mrpt::obs::CObservation3DRangeScan (RGB-D or range-only).
///
/// YAML parameters (all optional; defaults from PairParams, docs/mrpt.md):
///   target_patch_area_m2: 0.004   neighbourhood_k: 30   candidates: 20   lambda: 0.7
///   mutual_check: true   min_inliers: 8   dense_rounds: 3   refine: true
#include "gasp/mrpt/observation_matcher.h"
#include "gasp/pipeline/pair_registration.h"

namespace gasp {

class ObservationMatcher_GASP : public ObservationMatcher {
  DEFINE_MRPT_OBJECT(ObservationMatcher_GASP, gasp)
 public:
  void initialize(const mrpt::containers::yaml& params) override;
  MatchConstraint match(const mrpt::obs::CObservation& a, const mrpt::obs::CObservation& b,
                        const std::optional<mrpt::poses::CPose3D>& initial_guess = std::nullopt) const override;

  PairParams params;  ///< the pipeline's parameters (initialize() sets them from YAML)
};

}  // namespace gasp
