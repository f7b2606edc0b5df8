#pragma once
/// \file slide_scan.h The slide scan: a pose whose *patch* problem left a direction unobservable
/// (RANSAC inliers on a floor and a wall only) is claimed after the dense rounds, but those rounds
/// start at the patch pose and move little along that direction when only small objects pin it:
/// the pose may have slid. The visibility check cannot see a slide: its gate is 21 cm at 3 m.
///
/// The scan moves the claimed pose along each unobservable direction of the patch problem
/// (rotation about the patch problem's scene centre with the translation it couples to, scaled so
/// that the offset is the RMS displacement of the source patches' centroids) from -range_m to
/// +range_m in steps of step_m, and measures at each offset how well the views agree: the share
/// of the depth samples of both views that land on the other view's measured surface within a
/// tight gate (depthAgreement, visibility_check.h; 1 cm + 0.5 cm/m^2 z^2). When the best offset
/// agrees more than the claimed pose by min_gain, the dense refinement runs again from it; its
/// pose replaces the claimed one when it still agrees more by min_gain and passes the visibility
/// check. Only a claimed pose (it passed the visibility check) is scanned: the scan never turns
/// a failure into an estimate (from failed poses it finds look-alike alignments of repeated
/// objects). Measured in docs/pipeline.md ("Slide scan").
#include <string>

namespace gasp {

struct SlideScanParams {
  bool enabled = true;
  /// Largest offset scanned on each side [m], as the RMS displacement of the source patches'
  /// centroids; a few times the slides seen on sparse scenes.
  double range_m = 0.30;
  /// Spacing of the offsets [m], well below the width of the agreement's peak at the right pose:
  /// the converged dense rounds leave slides of a few cm, which coarser offsets step over
  /// (docs/pipeline.md, "Converged dense rounds").
  double step_m = 0.01;
  /// Agreement gain (share of samples, in [0, 1]) over the claimed pose needed to move. Small:
  /// the converged dense rounds bring slid poses close, so moving them gains little, while right
  /// poses of real scenes are seldom moved (docs/pipeline.md, "Slide scan").
  double min_gain = 0.005;
  int pixel_step = 8;  ///< agreement sampled at every N-th pixel of both views (>= 1)
};

/// Throws gasp::Error naming the first invalid parameter.
void validate(const SlideScanParams& params);

/// What the slide scan did for one pair (PairResult::slide).
struct SlideScanReport {
  bool ran = false;    ///< the claimed pose's patch problem had unobservable directions
  bool moved = false;  ///< the pose was replaced by the refinement from the best offset
  double offset_m = 0.0;  ///< the best offset scanned (RMS displacement of the source patches) [m]
  double agreement_before = -1.0;  ///< depthAgreement of the claimed pose (-1: not measured)
  double agreement_best = -1.0;    ///< at the best offset, before refinement
  double agreement_after = -1.0;   ///< of the refined pose from the best offset (-1: not refined)
  std::string summary() const;     ///< one line for logs and programs
};

}  // namespace gasp
