#pragma once
/// \file ObservationMatcher_GASP.h GASP's pair pipeline (gasp/pipeline/pair_registration.h) as an
/// ObservationMatcher for mrpt::obs::CObservation3DRangeScan (RGB-D or range-only), and for two
/// rotating LiDARs' sweeps (CObservationRotatingScan, CObservationVelodyneScan, CObservationPointCloud;
/// range_view.h).
///
/// YAML parameters: every field of PairParams, all optional, under the keys of params_io.h
/// (docs/mrpt.md "Matching keys" lists them with their defaults), e.g.
///   candidates: 30   lambda: 0.7   min_inliers: 8   dense_gates_m: [0.1, 0.05, 0.03]
/// or the params file's form (sections, `params_file: PATH`), whose section `lidar` gives the
/// sweeps' values: two sweeps are matched with lidarPairParams(lidar, params), `params` made a
/// LiDAR's by its rules.
#include "gasp/mrpt/observation_matcher.h"
#include "gasp/pipeline/pair_registration.h"
#include "gasp/pipeline/range_view.h"

namespace gasp {

class ObservationMatcher_GASP : public ObservationMatcher {
  DEFINE_MRPT_OBJECT(ObservationMatcher_GASP, gasp)
 public:
  void initialize(const mrpt::containers::yaml& params) override;
  MatchConstraint match(const mrpt::obs::CObservation& a, const mrpt::obs::CObservation& b,
                        const std::optional<mrpt::poses::CPose3D>& initial_guess = std::nullopt) const override;

  PairParams params;  ///< the pipeline's parameters for depth images (initialize() sets them from YAML)
  LidarParams lidar;  ///< for two LiDAR sweeps: lidarPairParams(lidar, params) (the params file form's section lidar)
};

}  // namespace gasp
