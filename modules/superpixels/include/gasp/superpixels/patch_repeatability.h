#pragma once
/// \file patch_repeatability.h How repeatable patches are across two views with known relative
/// pose: the share of view A's patches, inside the overlap, that view B also has.
///
/// Definition (used in tests and docs/superpixels.md): patch a of A is *in the overlap* when its
/// centroid, mapped into B (T_b_a * c_a), projects inside B's image onto a pixel with valid depth
/// within visibility_tolerance of the mapped depth (so it is not occluded or out of range) and its
/// mapped normal faces B's camera. It is *repeated* when some patch b of B has its centroid within
/// one patch radius, (r_a + r_b) / 2 with r = sqrt(area / pi), of the mapped centroid and its
/// normal within max_normal_angle_deg of the mapped normal.
#include <opencv2/core.hpp>

#include "gasp/core/view_projection.h"
#include "gasp/core/pose.h"
#include "gasp/superpixels/surface_patch.h"

namespace gasp {

struct RepeatabilityParams {
  double max_normal_angle_deg = 10.0;
  double visibility_tolerance_m = 0.05;    ///< plus visibility_tolerance_rel * depth
  double visibility_tolerance_rel = 0.03;
};

struct RepeatabilityResult {
  int patches_a = 0;   ///< patches of view A
  int in_overlap = 0;  ///< of those, inside the overlap
  int repeated = 0;    ///< of those, with a partner in B
  double fraction() const { return in_overlap ? static_cast<double>(repeated) / in_overlap : 0.0; }
};

/// depth_b: B's depth image [m] (CV_32FC1) with intrinsics_b; T_b_a maps A's camera frame to B's.
RepeatabilityResult measureRepeatability(const SuperpixelSegmentation& a, const SuperpixelSegmentation& b,
                                         const cv::Mat& depth_b, const ViewProjection& intrinsics_b,
                                         const Isometry3& T_b_a, const RepeatabilityParams& params = {});

}  // namespace gasp
