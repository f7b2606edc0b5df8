#pragma once
/// \file truncated_score.h The score of a pose against the dense terms gathered at it: the
/// objective of the dense rounds' line search (dense_rounds.h, DenseRoundsSettings::line_search).
///
/// The terms of a round are gathered at one pose (projective pixel terms whose target point lies
/// within the gate g of the mapped source point, edge terms whose nearest target edge point lies
/// within the edge gate); a solve on them can move the pose further than the gate, where they no
/// longer say where the surfaces are. A step is judged afresh: the terms are gathered again where
/// it lands and
///   score(T) = sum_i w_i max(0, g_i^2 - r_i^2),   r_i = n_i . (T p_i - q_i),
/// with w_i the term's weight and g_i its gate: a truncated quadratic (as in MSAC: Torr and
/// Zisserman, 2000) of the point-to-plane residual the refinement minimises. A point with no
/// partner within its gate, or on no depth, contributes 0. The gate is on the points' distance,
/// which is at least |r|, so a term can score up to g^2 until its point crosses the gate: the
/// score is not continuous there; the continuous alternative, scoring the gated distance itself,
/// is compared in docs/pipeline.md, "Line search at the last gate". An edge point
/// gives two terms, one per plane through the edge line. Larger is better. Terms with a
/// non-finite contribution (point, normal or weight) score 0.
#include <cstddef>
#include <vector>

#include "gasp/core/pose.h"
#include "gasp/registration/correspondence.h"

namespace gasp {

/// Dense terms gathered at one pose with their gates: the first `pixel_terms` are pixel terms
/// (gate pixel_gate_m), the rest edge terms (gate edge_gate_m).
struct GatedTerms {
  std::vector<PointToPlane> terms;
  std::size_t pixel_terms = 0;
  double pixel_gate_m = 0.0;
  double edge_gate_m = 0.0;
};

/// The score above at T_target_source; 0 for no terms. Never throws.
double truncatedScore(const GatedTerms& gathered, const Isometry3& T_target_source);

}  // namespace gasp
