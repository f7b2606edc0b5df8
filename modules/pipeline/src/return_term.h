#pragma once
/// \file return_term.h (private) One point-to-plane term on a sweep's returns, shared by the
/// returns' rounds (returns_stage.cpp) and the sweeps' motion (sweep_motion.cpp).
#include <Eigen/Core>

#include "gasp/pipeline/returns_stage.h"

namespace gasp {

/// The term of a point `pt` already in the target sweep's frame, as returnTerms() takes it: the
/// target's return of nearest direction with a normal (within `look_up_columns`), seen at an
/// incidence whose cosine is at least `min_cos`, with the point within `gate` of the term's
/// plane and within the gate plus a cell's footprint of the return across it. Sets the plane's
/// point (SweepReturns::surfaceNear) and normal and gives the return's index, or -1 for no term.
int returnTerm(const Eigen::Vector3d& pt, const SweepReturns& target, double gate, int look_up_columns, double min_cos,
               Eigen::Vector3d& plane_point, Eigen::Vector3d& normal);

}  // namespace gasp
