#include "gasp/pipeline/pair_registration.h"

#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <chrono>
#include <optional>
#include <cmath>
#include <cstdio>
#include <memory>

#include "gasp/core/error.h"
#include "gasp/core/stopwatch.h"
#include "gasp/superpixels/depth_superpixels.h"
#include "dense_refinement.h"

namespace gasp {

namespace {

std::vector<PatchCorrespondence> toCorrespondences(const std::vector<PatchAssociation>& associations,
                                                   const SuperpixelSegmentation& a, const SuperpixelSegmentation& b) {
  std::vector<PatchCorrespondence> out;
  out.reserve(associations.size());
  for (const auto& s : associations) {
    const auto& pa = a.patches[static_cast<std::size_t>(s.a)];
    const auto& pb = b.patches[static_cast<std::size_t>(s.b)];
    // A lower edit distance is more evidence: weight 1 - D_hat in [0, 1].
    out.push_back({pa.centroid, pa.normal.normalized(), pb.centroid, pb.normal.normalized(),
                   std::max(0.0, 1.0 - s.distance)});
  }
  return out;
}

/// The visibility check's parameters for a pose: a pose from the wider, less precise one-way
/// hypothesis set must explain the views better.
VisibilityCheckParams visibilityParams(const PairParams& params, bool used_one_way) {
  VisibilityCheckParams visibility = params.visibility;
  if (used_one_way)
    visibility.max_violation_ratio = std::min(visibility.max_violation_ratio, params.one_way_max_violation_ratio);
  return visibility;
}

/// The free-space check of a claimed pose (visibility_check.h): a failure withdraws the claim.
/// `done`: the check of this pose with these parameters, when already run.
void verify(const DepthView& source, const DepthView& target, const PairParams& params, PairResult& r,
            const std::optional<VisibilityCheck>& done = std::nullopt) {
  if (!r.pose.success) return;
  const auto t0 = std::chrono::steady_clock::now();
  r.visibility = done ? *done : checkVisibility(source, target, r.pose.T_target_source, visibilityParams(params, r.used_one_way));
  r.timings.dense_ms += msSince(t0);
  if (!r.visibility.passed) {
    r.pose.success = false;
    r.pose.reason = r.visibility.reason;
    r.visibility_refused = r.visibility.free_space_refused;
  }
}

}  // namespace

void validate(const PairParams& p) {
  validate(p.superpixels);
  validate(p.association);
  validate(p.pose);
  validate(p.projective);
  validate(p.edges);
  if (!(p.wide_edge_gate_factor == 0.0 || p.wide_edge_gate_factor >= 1.0) || !std::isfinite(p.wide_edge_gate_factor))
    throw Error("PairParams: wide_edge_gate_factor must be 0 (off) or finite and >= 1");
  if (!(p.wide_edge_min_paired_share >= 0.0 && p.wide_edge_min_paired_share <= 1.0))
    throw Error("PairParams: wide_edge_min_paired_share must be in [0, 1]");
  validate(p.dense_degeneracy);
  validate(p.slide_scan);
  validate(p.visibility);
  validate(p.guided);
  validate(p.model_error);
  if (!(p.one_way_max_violation_ratio >= 0.0 && p.one_way_max_violation_ratio <= 1.0))
    throw Error("PairParams: one_way_max_violation_ratio must be in [0, 1]");
  if (p.min_guided_support < 3) throw Error("PairParams: min_guided_support must be >= 3");
  if (!(p.view_degeneracy.min_eigenvalue_ratio >= 0 && p.view_degeneracy.min_eigenvalue_ratio < 1))
    throw Error("PairParams: view_degeneracy.min_eigenvalue_ratio must be in [0, 1)");
  if (p.dense_rounds < 0) throw Error("PairParams: dense_rounds must be >= 0");
  if (p.dense_max_rounds < 0) throw Error("PairParams: dense_max_rounds must be >= 0");
  if (!(p.dense_converged_m >= 0) || !std::isfinite(p.dense_converged_m))
    throw Error("PairParams: dense_converged_m must be finite and >= 0");
  if (!(p.dense_extrapolation_max >= 0) || !std::isfinite(p.dense_extrapolation_max))
    throw Error("PairParams: dense_extrapolation_max must be finite and >= 0");
  if (p.dense_line_search_halvings < 0) throw Error("PairParams: dense_line_search_halvings must be >= 0");
  if (p.min_dense_terms < 0) throw Error("PairParams: min_dense_terms must be >= 0");
  if (!(p.retry_area_factor == 0.0 || (p.retry_area_factor >= 0.01 && p.retry_area_factor < 1.0)))
    throw Error("PairParams: retry_area_factor must be 0 (off) or in [0.01, 1)");
  if (p.dense_rounds > 0 && p.dense_gates_m.empty()) throw Error("PairParams: dense_gates_m is empty");
  for (double g : p.dense_gates_m)
    if (!(g > 0) || !std::isfinite(g)) throw Error("PairParams: dense gates must be finite and > 0");
}

namespace {

/// registerViews() at the scale of the views given (no retry).
PairResult registerAtScale(const DepthView& source, const DepthView& target, const PairParams& params) {
  PairResult r;
  for (const auto* view : {&source, &target}) {
    const auto d = analyseViewGeometry(view->segmentation, params.view_degeneracy);
    if (d.degenerate) {
      r.pose.degenerate = true;
      r.pose.information_eigenvalues = d.eigenvalues;
      r.pose.unobservable_directions = d.unobservable_directions;
      r.pose.reason = std::string("degenerate scene: the ") + (view == &source ? "source" : "target") +
                      " view's geometry leaves free: " + d.reason;
      return r;
    }
  }
  auto t0 = std::chrono::steady_clock::now();
  const auto ga = toPatchGeometry(source.segmentation.patches), gb = toPatchGeometry(target.segmentation.patches);
  std::vector<std::vector<Feature>> qa, qb;
  tbb::parallel_invoke([&] { qa = computeFeatureSets(ga, params.association.feature_sets); },
                       [&] { qb = computeFeatureSets(gb, params.association.feature_sets); });
  const double features_ms = msSince(t0);
  r.association = associateFeatureSets(qa, qb, params.association);
  r.association.stats.features_ms = features_ms;
  r.timings.association_ms = msSince(t0);
  if (r.association.associations.empty() && r.association.one_way.empty()) {
    r.pose.reason = "no associations: " + r.association.reason;
    return r;
  }

  PoseEstimationParams pose_params = params.pose;
  pose_params.refine = params.refine;
  const auto attempt = [&](std::vector<PatchAssociation> used) {
    r.used = std::move(used);
    r.correspondences = toCorrespondences(r.used, source.segmentation, target.segmentation);
    r.pose = estimatePose(r.correspondences, pose_params);
    r.timings.ransac_ms += r.pose.ransac_ms;
    r.timings.refine_ms += r.pose.refine_ms;
  };
  // A pose found by RANSAC whose patch problem is degenerate (few inliers on few planes) goes on
  // to the dense rounds: the pixels of the whole overlap may observe what the patches did not.
  // The dense problem then gives the verdict.
  const auto poseFound = [&] { return r.pose.success || (r.pose.degenerate && !r.pose.inliers.empty()); };
  // Guided verification of the pose estimatePose() gave (RANSAC, then the patch refinement): at
  // least min_guided_support source patches must find a partner there (guided_association.h).
  // With guided_densify the guided associations then replace the correspondences.
  std::vector<PatchAssociation> guided_at_pose;
  const auto verified = [&]() -> bool {
    if (!poseFound()) return false;
    if (!params.guided_verification) return true;
    const auto tg = std::chrono::steady_clock::now();
    guided_at_pose = guidedAssociations(ga, gb, qa, qb, r.pose.T_target_source, params.association, params.guided);
    r.timings.guided_ms += msSince(tg);
    r.guided_support = static_cast<int>(guided_at_pose.size());
    if (r.guided_support < params.min_guided_support) {
      r.pose.success = false;
      r.pose.reason = "guided verification: " + std::to_string(r.guided_support) +
                      " source patches find a partner that agrees with the pose (min_guided_support " +
                      std::to_string(params.min_guided_support) + ")";
      return false;
    }
    if (!params.guided_densify) return true;
    attempt(guided_at_pose);
    if (poseFound()) return true;
    r.pose.reason = "on the guided associations: " + r.pose.reason;
    return false;
  };
  bool ok = false;
  if (!r.association.associations.empty()) {
    attempt(r.association.associations);
    ok = verified();
  } else {
    r.pose.reason = "no mutual associations";
  }
  // The one-way fallback: when the mutual associations give no pose, or one that fails the guided
  // verification.
  if (!ok && params.one_way_fallback && !r.association.one_way.empty()) {
    const std::string mutual_reason = r.pose.reason;
    std::vector<PatchAssociation> wider = r.association.associations;
    wider.insert(wider.end(), r.association.one_way.begin(), r.association.one_way.end());
    std::sort(wider.begin(), wider.end(), [](const PatchAssociation& x, const PatchAssociation& y) { return x.a < y.a; });
    attempt(std::move(wider));
    r.used_one_way = true;
    ok = verified();
    if (!ok) r.pose.reason = "mutual associations: " + mutual_reason + "; with one-way partners: " + r.pose.reason;
  }
  if (!ok) return r;

  if (!params.refine || params.dense_rounds == 0) {
    verify(source, target, params, r);
    if (r.pose.success && params.guided_verification) {
      if (params.guided_densify) {  // the pose moved since the verification
        const auto tg = std::chrono::steady_clock::now();
        guided_at_pose = guidedAssociations(ga, gb, qa, qb, r.pose.T_target_source, params.association, params.guided);
        r.timings.guided_ms += msSince(tg);
      }
      r.verified = std::move(guided_at_pose);
    }
    return r;
  }

  // Dense rounds: the patch inliers stay in the problem (they anchor it where pixels are few).
  t0 = std::chrono::steady_clock::now();
  std::vector<PatchCorrespondence> inliers;
  for (int i : r.pose.inliers) inliers.push_back(r.correspondences[static_cast<std::size_t>(i)]);
  const detail::DenseOutcome dense =
      detail::refineDense(source, target, r.pose, inliers, params, visibilityParams(params, r.used_one_way));
  r.pose = dense.pose;
  r.dense_unobservable = !r.pose.success && r.pose.degenerate;
  r.dense_terms = dense.rounds.terms;
  r.dense_rounds_run = dense.rounds.run;
  r.dense_last_step_m = dense.rounds.last_step_m;
  r.dense_steps_shortened = dense.rounds.shortened;
  r.dense_line_search_stopped = dense.rounds.line_search_stopped;
  r.wide_edge_pose = dense.wide_edge_pose;
  r.edge_paired_share = dense.edge_paired_share;
  r.slide = dense.slide;
  r.timings.dense_ms = msSince(t0);
  if (r.pose.success && r.dense_terms < params.min_dense_terms) {
    r.pose.success = false;
    r.pose.reason = "dense refinement: only " + std::to_string(r.dense_terms) +
                    " pixel and edge terms agree with the pose (min_dense_terms " +
                    std::to_string(params.min_dense_terms) + "): it puts too little of one view onto the other";
  }
  verify(source, target, params, r, dense.check);
  if (r.pose.success && params.guided_verification) {
    t0 = std::chrono::steady_clock::now();
    r.verified = guidedAssociations(ga, gb, qa, qb, r.pose.T_target_source, params.association, params.guided);
    r.timings.guided_ms += msSince(t0);
  }
  return r;
}

}  // namespace

DepthView finerScaleView(const DepthView& view, double area_factor) {
  SuperpixelParams sp = view.superpixels;
  sp.target_patch_area_m2 *= area_factor;
  return makeDepthView(view.depth_m, view.intrinsics, sp);
}

PairParams finerScaleParams(const PairParams& params) {
  PairParams fine = params;
  fine.retry_area_factor = 0.0;
  fine.one_way_fallback = false;
  // Smaller patches carry less distinctive neighbourhoods: like a one-way pose, a retry pose must
  // explain the views better (wrong retry poses on look-alike synthetic structure had 12-23 %
  // violations, right ones at most 3.3 %; docs/pipeline.md).
  fine.visibility.max_violation_ratio =
      std::min(params.visibility.max_violation_ratio, params.one_way_max_violation_ratio);
  return fine;
}

bool finerScaleRetryApplies(const PairResult& r, const DepthView& source, const DepthView& target) {
  // No retry for a degenerate view (no scale can fix it) nor for a degenerate patch problem without
  // dense rounds: finer patches on the same few planes add inliers, not constraints (docs/pipeline.md
  // step 6). A dense problem that is unobservable at RANSAC's pose says less: a pose from a handful
  // of wrong inliers maps little of one view onto the other. The retry's own dense rounds judge again.
  const bool degenerate = r.pose.degenerate && !r.dense_unobservable;
  return !r.pose.success && !degenerate && !source.depth_m.empty() && !target.depth_m.empty();
}

std::string finerScaleReason(double area_factor, const std::string& reason) {
  char factor[32];
  std::snprintf(factor, sizeof factor, "%g", area_factor);
  return std::string("at ") + factor + "x the patch area: " + reason;
}

std::pair<const DepthView*, const DepthView*> viewsOf(const PairResult& r, const DepthView& source,
                                                      const DepthView& target) {
  if (r.retry_views) return {&r.retry_views->first, &r.retry_views->second};
  return {&source, &target};
}

namespace {

/// registerViews() but for the edge information.
PairResult registerWithRetry(const DepthView& source, const DepthView& target, const PairParams& params) {
  PairResult r = registerAtScale(source, target, params);
  if (params.retry_area_factor == 0.0 || !finerScaleRetryApplies(r, source, target)) return r;
  // Finer-scale retry (PairParams::retry_area_factor): each view segmented again with its own
  // parameters at the smaller area; mutual associations only.
  const auto t0 = std::chrono::steady_clock::now();
  const PairParams fine = finerScaleParams(params);
  const double f = params.retry_area_factor;
  auto views = std::make_shared<std::pair<DepthView, DepthView>>();
  try {
    tbb::parallel_invoke([&] { views->first = finerScaleView(source, f); },
                         [&] { views->second = finerScaleView(target, f); });
  } catch (const std::exception& e) {  // e.g. a depth image that does not match its intrinsics
    r.retried = true;
    r.timings.retry_segmentation_ms = msSince(t0);
    r.pose.reason += "; " + finerScaleReason(f, std::string("segmentation failed: ") + e.what());
    return r;
  }
  const double segmentation_ms = msSince(t0);
  PairResult retry = registerAtScale(views->first, views->second, fine);
  PairTimings total = r.timings;
  total.addStages(retry.timings);
  total.retry_segmentation_ms = segmentation_ms;
  if (retry.pose.success) {
    retry.retried = true;
    retry.retry_views = std::move(views);
    retry.timings = total;
    return retry;
  }
  r.retried = true;
  r.timings = total;
  r.pose.reason += "; " + finerScaleReason(f, retry.pose.reason);
  r.visibility_refused = r.visibility_refused || retry.visibility_refused;
  return r;
}

}  // namespace

PairResult registerViews(const DepthView& source, const DepthView& target, const PairParams& params) {
  validate(params);
  PairResult r = registerWithRetry(source, target, params);
  if (r.pose.success) {
    try {
      r.edge_information = informationWithModelError(r.pose.information, params.model_error);
    } catch (const Error& e) {  // a claimed pose's information is positive definite; if not, no claim
      r.pose.success = false;
      r.pose.reason = std::string("edge information: ") + e.what();
    }
  }
  return r;
}

}  // namespace gasp
