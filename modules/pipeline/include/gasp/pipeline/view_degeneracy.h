#pragma once
/// \file view_degeneracy.h Whether the geometry of one view can fix a relative pose at all,
/// before any association: a single plane leaves two translations and one rotation free, parallel
/// planes (a corridor) leave a translation free. Each patch contributes its point-to-plane row
/// J = [n^T, (c x n)^T] (the residual's derivative for the left perturbation of
/// registration_result.h), weighted by its area: I = sum_i area_i J_i^T J_i. The verdict is
/// analyseDegeneracy() on I (conditioned about the area-weighted centre) with the eigenvalue
/// ratio alone: a single plane or a corridor falls below the default ratio, a floor with one
/// object on it lies above it (the measured ratios are in docs/pipeline.md).
#include "gasp/registration/degeneracy.h"
#include "gasp/superpixels/surface_patch.h"

namespace gasp {

/// A patch that counts in a view's plane geometry: finite centroid and normal, a normal of
/// non-zero length and a positive area.
inline bool countsInViewGeometry(const SurfacePatch& p) {
  return p.centroid.allFinite() && p.normal.allFinite() && p.area_m2 > 0 && p.normal.squaredNorm() >= 1e-12;
}

struct ViewDegeneracyParams {
  double min_eigenvalue_ratio = 1e-3;  ///< smallest / largest eigenvalue of the conditioned I
};

/// The analysis of a view's patches. A view without patches is degenerate (reason says so).
DegeneracyAnalysis analyseViewGeometry(const SuperpixelSegmentation& view, const ViewDegeneracyParams& params = {});

}  // namespace gasp
