#include "gasp/pipeline/pair_registration.h"

#include <chrono>
#include <cmath>

#include "gasp/core/error.h"
#include "gasp/superpixels/depth_superpixels.h"

namespace gasp {

namespace {

double msSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

std::vector<PatchCorrespondence> toCorrespondences(const AssociationResult& r, const SuperpixelSegmentation& a,
                                                   const SuperpixelSegmentation& b) {
  std::vector<PatchCorrespondence> out;
  out.reserve(r.associations.size());
  for (const auto& s : r.associations) {
    const auto& pa = a.patches[static_cast<std::size_t>(s.a)];
    const auto& pb = b.patches[static_cast<std::size_t>(s.b)];
    // A lower edit distance is more evidence: weight 1 - D_hat in [0, 1].
    out.push_back({pa.centroid, pa.normal.normalized(), pb.centroid, pb.normal.normalized(),
                   std::max(0.0, 1.0 - s.distance)});
  }
  return out;
}

/// The free-space check of a claimed pose (visibility_check.h): a failure withdraws the claim.
void verify(const DepthView& source, const DepthView& target, const PairParams& params, PairResult& r) {
  if (!r.pose.success) return;
  const auto t0 = std::chrono::steady_clock::now();
  r.visibility = checkVisibility(source, target, r.pose.T_target_source, params.visibility);
  r.timings.dense_ms += msSince(t0);
  if (!r.visibility.passed) {
    r.pose.success = false;
    r.pose.reason = r.visibility.reason;
  }
}

}  // namespace

void validate(const PairParams& p) {
  validate(p.superpixels);
  validate(p.association);
  validate(p.pose);
  validate(p.projective);
  validate(p.dense_degeneracy);
  validate(p.visibility);
  if (!(p.view_degeneracy.min_eigenvalue_ratio >= 0 && p.view_degeneracy.min_eigenvalue_ratio < 1))
    throw Error("PairParams: view_degeneracy.min_eigenvalue_ratio must be in [0, 1)");
  if (p.dense_rounds < 0) throw Error("PairParams: dense_rounds must be >= 0");
  if (p.dense_rounds > 0 && p.dense_gates_m.empty()) throw Error("PairParams: dense_gates_m is empty");
  for (double g : p.dense_gates_m)
    if (!(g > 0) || !std::isfinite(g)) throw Error("PairParams: dense gates must be finite and > 0");
}

PairResult registerViews(const DepthView& source, const DepthView& target, const PairParams& params) {
  validate(params);
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
  r.association = associateViews(toPatchGeometry(source.segmentation.patches),
                                 toPatchGeometry(target.segmentation.patches), params.association);
  r.timings.association_ms = msSince(t0);
  if (r.association.associations.empty()) {
    r.pose.reason = "no associations: " + r.association.reason;
    return r;
  }
  r.correspondences = toCorrespondences(r.association, source.segmentation, target.segmentation);

  PoseEstimationParams pose_params = params.pose;
  pose_params.refine = params.refine;
  r.pose = estimatePose(r.correspondences, pose_params);
  r.timings.ransac_ms = r.pose.ransac_ms;
  r.timings.refine_ms = r.pose.refine_ms;
  // A pose found by RANSAC whose patch problem is degenerate (few inliers on few planes) goes on
  // to the dense rounds: the pixels of the whole overlap may observe what the patches did not.
  // The dense problem then gives the verdict.
  const bool pose_found = r.pose.success || (r.pose.degenerate && !r.pose.inliers.empty());
  if (!pose_found) return r;
  if (!params.refine || params.dense_rounds == 0) {
    verify(source, target, params, r);
    return r;
  }

  // Dense rounds: the patch inliers stay in the problem (they anchor it where pixels are few).
  t0 = std::chrono::steady_clock::now();
  std::vector<PatchCorrespondence> inliers;
  for (int i : r.pose.inliers) inliers.push_back(r.correspondences[static_cast<std::size_t>(i)]);
  RegistrationResult current = r.pose;
  for (int round = 0; round < params.dense_rounds; ++round) {
    ProjectiveTermParams proj = params.projective;
    const std::size_t g = std::min<std::size_t>(static_cast<std::size_t>(round), params.dense_gates_m.size() - 1);
    proj.max_distance_m = params.dense_gates_m[g];
    const auto terms = projectiveTerms(source, target, current.T_target_source, proj);
    r.dense_terms = static_cast<int>(terms.size());
    RefinementParams refinement = params.pose.refinement;
    refinement.degeneracy = params.dense_degeneracy;
    RegistrationResult next = refinePose(inliers, current.T_target_source, refinement, terms);
    if (!next.success) {
      // The dense problem may be degenerate or fail where the patch problem was not: then no
      // pose is claimed (never a silently weaker one).
      next.inliers = r.pose.inliers;
      next.num_inliers = r.pose.num_inliers;
      next.ransac_iterations = r.pose.ransac_iterations;
      next.reason = "dense refinement: " + next.reason;
      current = next;
      break;
    }
    current = next;
  }
  current.inliers = r.pose.inliers;
  current.num_inliers = r.pose.num_inliers;
  current.ransac_iterations = r.pose.ransac_iterations;
  current.ransac_ms = r.pose.ransac_ms;
  current.refine_ms = r.pose.refine_ms;
  r.pose = current;
  r.timings.dense_ms = msSince(t0);
  verify(source, target, params, r);
  return r;
}

}  // namespace gasp
