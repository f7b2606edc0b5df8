#pragma once
/// \file view_degeneracy.h Whether the geometry of one view can fix a relative pose at all,
/// before any association: a single plane leaves two translations and one rotation free, parallel
/// planes (a corridor) leave a translation free. Each patch contributes its point-to-plane row
/// J = [n^T, (c x n)^T] (the residual's derivative for the left perturbation of
/// registration_result.h), weighted by its area: I = sum_i area_i J_i^T J_i. The verdict is
/// analyseDegeneracy() on I (conditioned about the area-weighted centre) with the eigenvalue
/// ratio alone. Measured (docs/pipeline.md): noisy synthetic single plane 3e-4 - 6e-4, corridor
/// 7e-5 - 2e-4; fr3_cabinet views (floor and one cabinet) 2e-3 - 5e-3, desk and room views more.
#include "gasp/registration/degeneracy.h"
#include "gasp/superpixels/surface_patch.h"

namespace gasp {

struct ViewDegeneracyParams {
  double min_eigenvalue_ratio = 1e-3;  ///< smallest / largest eigenvalue of the conditioned I
};

/// The analysis of a view's patches. A view without patches is degenerate (reason says so).
DegeneracyAnalysis analyseViewGeometry(const SuperpixelSegmentation& view, const ViewDegeneracyParams& params = {});

}  // namespace gasp
