#pragma once
/// \file association_quality.h Whether associations are right, given the true relative pose.
///
/// Definition (used everywhere in GASP: tests, gasp-associate, docs/association.md): an
/// association (a, b) is *correct* when a and b are the same physical surface: a's centroid,
/// mapped into B by the true T_b_a, lies within one patch radius, (r_a + r_b) / 2 with
/// r = sqrt(area / pi), of b's centroid, and a's mapped normal is within max_normal_angle_deg
/// (20 deg) of b's normal. *Precision* = correct / associations made. *Density* = associations
/// made / patches of A that have a true partner in B inside the overlap (the repeatable patches of
/// patch_repeatability.h, with the same radius and angle).
#include <opencv2/core.hpp>

#include <vector>

#include "gasp/association/view_association.h"
#include "gasp/core/camera_intrinsics.h"
#include "gasp/core/pose.h"
#include "gasp/superpixels/surface_patch.h"

namespace gasp {

struct AssociationQuality {
  int associations = 0;
  int correct = 0;
  int with_true_partner = 0;  ///< patches of A with a true partner inside the overlap
  double precision() const { return associations ? static_cast<double>(correct) / associations : 0.0; }
  double density() const {
    return with_true_partner ? static_cast<double>(associations) / with_true_partner : 0.0;
  }
};

/// Angle used by the definition above [deg].
inline constexpr double kCorrectAssociationMaxNormalAngleDeg = 20.0;

/// True when patch a (view A) and patch b (view B) are the same surface under T_b_a.
bool isSameSurface(const SurfacePatch& a, const SurfacePatch& b, const Isometry3& T_b_a,
                   double max_normal_angle_deg = kCorrectAssociationMaxNormalAngleDeg);

AssociationQuality evaluateAssociations(const std::vector<PatchAssociation>& associations,
                                        const SuperpixelSegmentation& a, const SuperpixelSegmentation& b,
                                        const cv::Mat& depth_b, const CameraIntrinsics& intrinsics_b,
                                        const Isometry3& T_b_a);

}  // namespace gasp
