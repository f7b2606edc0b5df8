#include "gasp/registration/correspondence.h"

#include <cmath>

namespace gasp {
namespace {

constexpr double kUnitTolerance = 1e-3;

/// Why one term is unusable, or empty.
std::string invalidTerm(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& n,
                        double weight, const char* normal_name) {
  if (!p.allFinite() || !q.allFinite() || !n.allFinite() || !std::isfinite(weight)) return "non-finite component";
  if (std::abs(n.norm() - 1.0) > kUnitTolerance) return std::string(normal_name) + " is not a unit vector";
  if (weight < 0.0) return "negative weight";
  return {};
}

}  // namespace

std::string invalidInput(const std::vector<PatchCorrespondence>& correspondences) {
  for (std::size_t i = 0; i < correspondences.size(); ++i) {
    const auto& c = correspondences[i];
    std::string why = invalidTerm(c.p_source, c.p_target, c.n_source, c.weight, "n_source");
    if (why.empty()) why = invalidTerm(c.p_source, c.p_target, c.n_target, c.weight, "n_target");
    if (!why.empty()) return "correspondence " + std::to_string(i) + ": " + why;
  }
  return {};
}

std::string invalidInput(const std::vector<PointToPlane>& terms) {
  for (std::size_t i = 0; i < terms.size(); ++i) {
    const auto& t = terms[i];
    const std::string why = invalidTerm(t.p_source, t.q_target, t.n_target, t.weight, "n_target");
    if (!why.empty()) return "point-to-plane term " + std::to_string(i) + ": " + why;
  }
  return {};
}

}  // namespace gasp
