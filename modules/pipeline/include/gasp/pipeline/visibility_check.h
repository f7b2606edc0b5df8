#pragma once
/// \file visibility_check.h Verification of a relative pose by free-space consistency, so that an
/// alignment of look-alike parts of two views (repeated objects, symmetric structure) is not
/// claimed. Each sampled source pixel is mapped by T_target_source and projected into the target
/// image; with z its depth along the target ray and z_t the depth the target measured there:
///   consistent  |z - z_t| <= gate(z_t)
///   occluded    z > z_t + gate       (behind a surface the target saw: allowed)
///   violation   z < z_t - gate       (in space the target saw as empty: contradiction)
/// with gate(z) = gate_m + gate_per_m2 * z^2 (Kinect noise grows with z^2). The pose passes when
/// violations are at most max_violation_ratio of (consistent + violations) in both directions and
/// in the lesser direction at most max_two_way_violation_ratio, and
/// occluded samples at most max_occluded_ratio of all samples that land on the other view's depth,
/// in both directions: a pose that puts most of a view behind the other view's surfaces (a
/// flipped alignment of a desk plane) contradicts nothing but explains nothing either, while right
/// poses leave well under half of a view occluded.
/// max_violation_ratio 0.15: well above what right poses of deskewed views violate, below what
/// flipped and look-alike alignments do. Trade-off (docs/pipeline.md): an object that appears
/// between the views also violates one direction, so an occluder covering more than ~15 % of the
/// overlap gives no estimate.
/// max_two_way_violation_ratio 0.05: an object that appears or vanishes between the views
/// violates one direction only, but a wrong alignment of look-alike structure violates both. A
/// pose fails when *both* directions exceed this share (the lesser direction,
/// violation_ratio_lesser); a wrong pose that violates only a little from both views still passes
/// (docs/pipeline.md, "Violations seen from both views"). The price: an object that *moved*
/// between the views (a walking person) violates both directions, and more than 5 % of the
/// overlap of such an object gives no estimate (docs/pipeline.md, "Objects that moved"). How
/// compact the violations are (violation_blob_share_lesser) is reported but decides nothing:
/// moved objects and wrong poses are both compact (same section).
#include <functional>
#include <string>

#include "gasp/core/pose.h"
#include "gasp/pipeline/depth_view.h"

namespace gasp {

struct VisibilityCheckParams {
  int pixel_step = 8;              ///< sample every N-th pixel in u and v (>= 1)
  double gate_m = 0.03;            ///< constant part of the gate [m]
  double gate_per_m2 = 0.02;       ///< depth-squared part of the gate [1/m]
  /// Widen the gate by the depth change of the target pixel's surface across half a pixel
  /// diagonal (depth x angle x tan(incidence), the pixel's patch normal): for coarse pixels, a
  /// LiDAR's binned cells (lidarPairParams). Off for a camera, whose checks were measured without.
  bool pixel_spread = false;
  double max_violation_ratio = 0.15;  ///< in [0, 1] (see above)
  double max_occluded_ratio = 0.5;   ///< in [0, 1]; 1 = no limit
  double max_two_way_violation_ratio = 0.05;  ///< in [0, 1]; 1 = no limit (see above)
  int min_consistent = 50;         ///< fewer consistent samples: the views do not overlap enough
};

void validate(const VisibilityCheckParams& params);

/// The gate of the test above where a point q (in the frame of view `to`) meets the depth z_t
/// that `to` measured at pixel (u, v): gate_m + gate_per_m2 z_t^2, and with pixel_spread the depth
/// change of that pixel's surface across half a pixel diagonal (depth x angle x tan(incidence),
/// the pixel's patch normal, the incidence clamped as the segmentation clamps it; 0 on a pixel
/// without a patch or outside the image). Negligible for a camera's pixels, a LiDAR cell's spread on a floor seen at a
/// low angle can be a metre. The free-space test and the likelihood's violations
/// (pose_likelihood.h) both use it. Keeps references to `to` and `params`.
class FreeSpaceGate {
 public:
  FreeSpaceGate(const DepthView& to, const VisibilityCheckParams& params);
  double operator()(int u, int v, const Eigen::Vector3d& q, double z_t) const;

 private:
  const DepthView& to_;
  const VisibilityCheckParams& params_;
  double half_pixel_rad_, min_cos_;
};

struct VisibilityCheck {
  bool passed = false;
  int consistent = 0, occluded = 0, violations = 0;  ///< summed over both directions
  double violation_ratio = 0.0;  ///< the worse direction
  double violation_ratio_lesser = 0.0;  ///< the other direction
  double occluded_ratio = 0.0;   ///< occluded / (consistent + occluded + violations), the worse direction
  /// Share of a direction's violating samples in its largest 8-connected region on the sampling
  /// grid (1 without violations): one compact object, or violations spread over the view. The
  /// smaller and the larger of the two directions' shares (not tied to violation_ratio's
  /// directions: the smaller share is the one that says whether *both* are compact). A
  /// diagnostic: no verdict rests on it. depthAgreement() does not measure it.
  double violation_blob_share_lesser = 1.0, violation_blob_share = 1.0;
  std::string reason;            ///< why it failed
  /// Failed on its violation or occlusion limits: the views contradict each other's free space
  /// (false when it failed for a non-finite pose or too little overlap, min_consistent).
  bool free_space_refused = false;
  /// consistent / (consistent + occluded + violations), both directions (0 without samples).
  double consistentShare() const {
    const int n = consistent + occluded + violations;
    return n > 0 ? static_cast<double>(consistent) / n : 0.0;
  }
};

/// A free-space test of a pose between two fixed views: checkVisibility() with fixed parameters.
/// What the certificate applies to a pose (certify_stage.h), handed to the stages that choose
/// between candidate poses (refine_stage.h).
using FreeSpaceTest = std::function<VisibilityCheck(const Isometry3& T_target_source)>;

/// Both directions (source into target, target into source).
VisibilityCheck checkVisibility(const DepthView& source, const DepthView& target, const Isometry3& T_target_source,
                                const VisibilityCheckParams& params = {});

/// The check's classes with a tight gate, 1 cm + 0.5 cm/m^2 z^2 (about twice the Kinect's noise
/// at 1-3 m), every `pixel_step`-th pixel and no pass criteria: depthAgreement()'s parameters.
VisibilityCheckParams agreementParams(int pixel_step = 8);

/// How well a pose explains the depth: consistent / (consistent + occluded + violations) of both
/// views' samples under agreementParams(pixel_step). The visibility check's gate (3 cm + 2 cm/m^2
/// z^2, 21 cm at 3 m) tells contradiction from consistency; this one ranks poses near each other
/// (the slide scan, slide_scan.h; gasp-pairs' `agreement` column). 0 when nothing lands.
double depthAgreement(const DepthView& source, const DepthView& target, const Isometry3& T_target_source,
                      int pixel_step = 8);

}  // namespace gasp
