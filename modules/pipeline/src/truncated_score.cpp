#include "gasp/pipeline/truncated_score.h"

#include <cmath>

namespace gasp {

double truncatedScore(const GatedTerms& gathered, const Isometry3& T_target_source) {
  double score = 0.0;
  for (std::size_t i = 0; i < gathered.terms.size(); ++i) {
    const PointToPlane& term = gathered.terms[i];
    const double g = i < gathered.pixel_terms ? gathered.pixel_gate_m : gathered.edge_gate_m;
    const double r = term.n_target.dot(T_target_source * term.p_source - term.q_target);
    const double contribution = term.weight * (g * g - r * r);
    if (std::isfinite(contribution) && contribution > 0.0) score += contribution;
  }
  return score;
}

}  // namespace gasp
