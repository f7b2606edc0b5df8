#pragma once
/// \file slide_scan.h The slide scan: a pose whose *patch* problem left a direction unobservable
/// (RANSAC inliers on a floor and a wall only) is claimed after the dense rounds, but those rounds
/// start at the patch pose and move little along that direction when only small objects pin it:
/// the pose may have slid. On the synthetic sparse scene (a room with one box, one cylinder and one
/// sphere) such poses were claimed 0.19-0.21 m / 3.2-3.4 deg off, with under 0.5 % violations --
/// at 3 m the visibility check's gate is 21 cm, so it cannot see a slide.
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
/// a failure into an estimate (from failed poses it found look-alike alignments of repeated boxes,
/// 0.29 m / 7.4 deg off). Measured in docs/pipeline.md ("Slide scan").
#include <string>

namespace gasp {

struct SlideScanParams {
  bool enabled = true;
  /// Largest offset scanned on each side [m], as the RMS displacement of the source patches'
  /// centroids. The sparse scene's slides were 0.08-0.11 m in this measure.
  double range_m = 0.30;
  /// Spacing of the offsets [m]; the agreement's peak at the right pose is 0.04-0.08 m wide. 0.01:
  /// after the converged dense rounds the sparse scene's 6 -> 12 stops 2.8 cm off, where 0.02 m
  /// offsets find no gain (docs/pipeline.md, "Converged dense rounds").
  double step_m = 0.01;
  /// Agreement gain (share of samples, in [0, 1]) over the claimed pose needed to move. With the
  /// converged dense rounds slid poses come closer and gain less (sparse 3 -> 13: 0.019);
  /// at 0.005 the scan moved no fr1_xyz pose and one fr3_cabinet_kf pose (21 -> 23, 2.9 -> 0.9 cm
  /// from TUM's reference, agreement 0.875 -> 0.907).
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
