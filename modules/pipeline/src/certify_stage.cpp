#include "gasp/pipeline/certify_stage.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "gasp/core/error.h"
#include "gasp/core/pose_perturbation.h"
#include "gasp/pipeline/pose_likelihood.h"
#include "gasp/registration/partial_pose.h"

namespace gasp {

void validate(const CertifyParams& p) {
  if (!(p.view_degeneracy.min_eigenvalue_ratio >= 0 && p.view_degeneracy.min_eigenvalue_ratio < 1))
    throw Error("certify: view_degeneracy.min_eigenvalue_ratio must be in [0, 1)");
  if (p.min_dense_terms < 0) throw Error("certify: min_dense_terms must be >= 0");
  validate(p.visibility);
  if (!(p.fallback_max_violation_ratio >= 0.0 && p.fallback_max_violation_ratio <= 1.0))
    throw Error("certify: fallback_max_violation_ratio must be in [0, 1]");
  validate(p.model_error);
  if (!(p.min_likelihood_ratio == 0.0 || p.min_likelihood_ratio >= 1.0) || !std::isfinite(p.min_likelihood_ratio))
    throw Error("certify: min_likelihood_ratio must be 0 (off) or finite and >= 1");
  if (!(p.violation_nats >= 0.0) || !std::isfinite(p.violation_nats))
    throw Error("certify: likelihood_violation_nats must be >= 0 and finite");
}

ViewsCertificate certifyViews(const DepthView& source, const DepthView& target, const CertifyParams& params) {
  ViewsCertificate out;
  for (const auto* view : {&source, &target}) {
    const auto d = analyseViewGeometry(view->segmentation, params.view_degeneracy);
    if (!d.degenerate) continue;
    (view == &source ? out.source_free : out.target_free) = d.unobservable_twists;
    const bool partial_possible = params.partial_poses && d.unobservable_directions.cols() > 0 &&
                                  d.unobservable_directions.cols() <= kMaxFreeDirections;
    if (partial_possible || out.refusal) continue;
    RegistrationResult r;
    r.degenerate = true;
    r.information_eigenvalues = d.eigenvalues;
    r.unobservable_directions = d.unobservable_directions;
    r.reason = std::string("degenerate scene: the ") + (view == &source ? "source" : "target") +
               " view's geometry leaves free: " + d.reason;
    out.refusal = std::move(r);
  }
  if (params.partial_poses && !out.refusal && out.source_free.cols() + out.target_free.cols() > 0) {
    out.source_plane = dominantPlane(source.segmentation);
    out.target_plane = dominantPlane(target.segmentation);
  }
  return out;
}

VisibilityCheckParams visibilityLimits(const CertifyParams& params, bool fallback) {
  VisibilityCheckParams visibility = params.visibility;
  if (fallback)
    visibility.max_violation_ratio = std::min(visibility.max_violation_ratio, params.fallback_max_violation_ratio);
  return visibility;
}

FreeSpaceTest freeSpaceTest(const DepthView& source, const DepthView& target, const CertifyParams& params,
                            bool fallback) {
  const VisibilityCheckParams visibility = visibilityLimits(params, fallback);
  return [&source, &target, visibility](const Isometry3& T_target_source) {
    return checkVisibility(source, target, T_target_source, visibility);
  };
}

namespace {

/// The directions the views leave free, as left perturbations of the pose: the source view's
/// move its camera frame, hence Ad(T) into the target frame's.
Eigen::Matrix<double, 6, Eigen::Dynamic> viewsFree(const RegistrationResult& pose, const ViewsCertificate& views) {
  Eigen::Matrix<double, 6, Eigen::Dynamic> more(6, views.source_free.cols() + views.target_free.cols());
  if (views.source_free.cols() > 0)
    more.leftCols(views.source_free.cols()) = adjoint(pose.T_target_source) * views.source_free;
  if (views.target_free.cols() > 0) more.rightCols(views.target_free.cols()) = views.target_free;
  return more;
}

}  // namespace

Certificate certify(const RegistrationResult& pose, std::optional<int> dense_terms, const FreeSpaceTest& free_space,
                    const std::optional<VisibilityCheck>& done, const ViewsCertificate& views,
                    const CertifyParams& params) {
  Certificate c;
  if (!pose.estimated() || (pose.partial && !params.partial_poses)) {
    c.reason = pose.reason;
    return c;
  }
  // The free directions in the pose's conditioned coordinates: the dense problem's and the views'.
  const Eigen::Matrix<double, 6, Eigen::Dynamic> views_free = viewsFree(pose, views);
  c.free_directions = unitedDirections(pose, views_free);
  if (c.free_directions.cols() > 0 && !params.partial_poses) {
    c.reason = "unobservable: " + directionsText(c.free_directions);
    c.not_aligned = views_free.cols() == 0;
    return c;
  }
  // A partial pose needs views whose own geometry leaves some direction free: where both views
  // fix every direction and the pose's terms do not, the structure that fixes them was not
  // brought into alignment -- what a wrong pose does.
  if (c.free_directions.cols() > 0 && views_free.cols() == 0) {
    c.reason = "unobservable: " + directionsText(c.free_directions) +
               ", which the views' own geometry fixes: the structure that fixes it is not aligned";
    c.not_aligned = true;
    return c;
  }
  if (c.free_directions.cols() > kMaxFreeDirections) {
    c.reason = "unobservable: " + directionsText(c.free_directions) + " (more than " +
               std::to_string(kMaxFreeDirections) + " directions: not even a plane is fixed)";
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
  c.partial = c.free_directions.cols() > 0;
  // The views leave directions free (above), so their dominant plane carries the pose.
  for (const auto* plane : {&views.source_plane, &views.target_plane}) {
    if (c.partial && *plane && (*plane)->ambiguous()) {
      c.reason = std::string("partial pose not unique: the ") + (plane == &views.source_plane ? "source" : "target") +
                 " view holds two large parallel planes, and its free directions leave which matches which open";
      c.partial = false;
      return c;
    }
  }
  try {
    if (c.partial) {
      RegistrationResult observed = pose;
      observed.unobservable_directions = c.free_directions;
      c.edge_information =
          observedInformationWithCovariance(observed, pose.information, modelErrorCovariance(params.model_error));
    } else {
      c.edge_information = informationWithModelError(pose.information, params.model_error);
    }
  } catch (const Error& e) {  // a claimed pose's information is positive definite where observed; if not, no claim
    c.reason = std::string("edge information: ") + e.what();
    c.partial = false;
    return c;
  }
  c.claimed = true;
  if (c.partial) c.reason = "partial pose, free: " + directionsText(c.free_directions);
  return c;
}

namespace {

/// The uniqueness test's likelihood: the free-space test's samples (every cell of a LiDAR's view)
/// and its gate for the violations.
PoseLikelihoodParams uniquenessLikelihood(const CertifyParams& params) {
  PoseLikelihoodParams likelihood;
  likelihood.pixel_step = params.visibility.pixel_step;
  likelihood.violation_nats = params.violation_nats;
  likelihood.free_space = params.visibility;
  return likelihood;
}

/// compareAlternative() with the ratio `ratio`(T_chosen, T_alternative, likelihood params).
template <typename Ratio>
Uniqueness compareWith(const DepthView& source, const RegistrationResult& chosen, const RegistrationResult& alternative,
                       double distinct_m, const CertifyParams& params, const Ratio& ratio) {
  Uniqueness u;
  if (params.min_likelihood_ratio == 0.0) return u;
  std::vector<Eigen::Vector3d> centroids;
  for (const auto& p : source.segmentation.patches)
    if (p.centroid.allFinite()) centroids.push_back(p.centroid);
  // The chosen pose moved along its free directions towards the alternative: what is left apart
  // is the difference in its observed directions.
  const Isometry3 nearest = chosen.partial ? withPrediction(chosen, alternative.T_target_source) : chosen.T_target_source;
  u.distance_m = rmsDisplacement(nearest, alternative.T_target_source, pointSpread(centroids));
  if (!(u.distance_m > distinct_m)) return u;
  const LikelihoodRatio lr = ratio(chosen.T_target_source, alternative.T_target_source, uniquenessLikelihood(params));
  if (lr.patches == 0) return u;  // no sample lands under both poses: nothing to compare
  u.tested = true;
  u.log_ratio = lr.log_ratio;
  u.standard_error = lr.standard_error;
  const double needed = std::max(std::log(params.min_likelihood_ratio), kUniquenessStandardErrors * lr.standard_error);
  if (u.log_ratio >= needed) return u;
  if (-u.log_ratio >= needed) {
    u.take_alternative = true;
    return u;
  }
  char buf[360];
  std::snprintf(buf, sizeof buf,
                "not unique: a distinct alternative pose (%.2f m away) explains the views almost as well "
                "(log-likelihood ratio %.1f +- %.1f; at least log %g and %g standard errors needed)",
                u.distance_m, u.log_ratio, u.standard_error, params.min_likelihood_ratio, kUniquenessStandardErrors);
  u.reason = buf;
  u.refused = true;
  return u;
}

}  // namespace

Uniqueness compareAlternative(const DepthView& source, const DepthView& target, const RegistrationResult& chosen,
                              const RegistrationResult& alternative, double distinct_m, const CertifyParams& params) {
  return compareWith(source, chosen, alternative, distinct_m, params,
                     [&](const Isometry3& T_a, const Isometry3& T_b, const PoseLikelihoodParams& likelihood) {
                       return logLikelihoodRatio(source, target, T_a, T_b, likelihood);
                     });
}

PoseSamples samplesForComparison(const DepthView& source, const DepthView& target, const RegistrationResult& chosen,
                                 const CertifyParams& params) {
  const PoseLikelihoodParams likelihood = uniquenessLikelihood(params);
  if (params.min_likelihood_ratio == 0.0) {  // the test is off: no comparison will read them
    PoseSamples none;
    none.T_target_source = chosen.T_target_source;
    none.pixel_step = likelihood.pixel_step;
    return none;
  }
  return poseSamples(source, target, chosen.T_target_source, likelihood);
}

Uniqueness compareAlternative(const DepthView& source, const DepthView& target, const RegistrationResult& chosen,
                              const RegistrationResult& alternative, double distinct_m, const CertifyParams& params,
                              const PoseSamples& chosen_samples) {
  if (!chosen.T_target_source.matrix().allFinite())  // no sample to keep: as the other overload
    return compareAlternative(source, target, chosen, alternative, distinct_m, params);
  if (chosen_samples.T_target_source.matrix() != chosen.T_target_source.matrix())
    throw Error("compareAlternative: the samples given are of another pose than the chosen one");
  return compareWith(source, chosen, alternative, distinct_m, params,
                     [&](const Isometry3&, const Isometry3& T_b, const PoseLikelihoodParams& likelihood) {
                       return logLikelihoodRatio(source, target, chosen_samples, T_b, likelihood);
                     });
}

Uniqueness compareAlternativeOnReturns(const DepthView& source, const DepthView& target, const RegistrationResult& chosen,
                                       const RegistrationResult& alternative, double distinct_m,
                                       const CertifyParams& params, double range_sigma_m, double max_incidence_deg) {
  if (!source.returns || !target.returns) return Uniqueness{};
  return compareWith(source, chosen, alternative, distinct_m, params,
                     [&](const Isometry3& T_a, const Isometry3& T_b, const PoseLikelihoodParams& likelihood) {
                       return returnsLogLikelihoodRatio(source, target, T_a, T_b, likelihood, range_sigma_m,
                                                        max_incidence_deg);
                     });
}

}  // namespace gasp
