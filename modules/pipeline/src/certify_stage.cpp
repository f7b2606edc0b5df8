#include "gasp/pipeline/certify_stage.h"

#include <algorithm>

#include "gasp/core/error.h"

namespace gasp {

void validate(const CertifyParams& p) {
  if (!(p.view_degeneracy.min_eigenvalue_ratio >= 0 && p.view_degeneracy.min_eigenvalue_ratio < 1))
    throw Error("certify: view_degeneracy.min_eigenvalue_ratio must be in [0, 1)");
  if (p.min_dense_terms < 0) throw Error("certify: min_dense_terms must be >= 0");
  validate(p.visibility);
  if (!(p.fallback_max_violation_ratio >= 0.0 && p.fallback_max_violation_ratio <= 1.0))
    throw Error("certify: fallback_max_violation_ratio must be in [0, 1]");
  validate(p.model_error);
}

std::optional<RegistrationResult> certifyViews(const DepthView& source, const DepthView& target,
                                               const CertifyParams& params) {
  for (const auto* view : {&source, &target}) {
    const auto d = analyseViewGeometry(view->segmentation, params.view_degeneracy);
    if (!d.degenerate) continue;
    RegistrationResult r;
    r.degenerate = true;
    r.information_eigenvalues = d.eigenvalues;
    r.unobservable_directions = d.unobservable_directions;
    r.reason = std::string("degenerate scene: the ") + (view == &source ? "source" : "target") +
               " view's geometry leaves free: " + d.reason;
    return r;
  }
  return std::nullopt;
}

FreeSpaceTest freeSpaceTest(const DepthView& source, const DepthView& target, const CertifyParams& params,
                            bool fallback) {
  VisibilityCheckParams visibility = params.visibility;
  if (fallback)
    visibility.max_violation_ratio = std::min(visibility.max_violation_ratio, params.fallback_max_violation_ratio);
  return [&source, &target, visibility](const Isometry3& T_target_source) {
    return checkVisibility(source, target, T_target_source, visibility);
  };
}

Certificate certify(const RegistrationResult& pose, std::optional<int> dense_terms, const FreeSpaceTest& free_space,
                    const std::optional<VisibilityCheck>& done, const CertifyParams& params) {
  Certificate c;
  if (!pose.success) {
    c.reason = pose.reason;
    return c;
  }
  if (dense_terms && *dense_terms < params.min_dense_terms) {
    c.reason = "dense refinement: only " + std::to_string(*dense_terms) +
               " pixel and edge terms agree with the pose (min_dense_terms " + std::to_string(params.min_dense_terms) +
               "): it puts too little of one view onto the other";
    return c;
  }
  c.visibility = done ? *done : free_space(pose.T_target_source);
  if (!c.visibility->passed) {
    c.reason = c.visibility->reason;
    c.free_space_refused = c.visibility->free_space_refused;
    return c;
  }
  try {
    c.edge_information = informationWithModelError(pose.information, params.model_error);
  } catch (const Error& e) {  // a claimed pose's information is positive definite; if not, no claim
    c.reason = std::string("edge information: ") + e.what();
    return c;
  }
  c.claimed = true;
  return c;
}

}  // namespace gasp
