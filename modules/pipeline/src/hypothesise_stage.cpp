#include "gasp/pipeline/hypothesise_stage.h"

#include <algorithm>
#include <chrono>
#include <utility>

#include "gasp/core/error.h"
#include "gasp/core/stopwatch.h"

namespace gasp {

namespace {

std::vector<PatchCorrespondence> toCorrespondences(const std::vector<PatchAssociation>& associations,
                                                   const AssociatedViews& a) {
  std::vector<PatchCorrespondence> out;
  out.reserve(associations.size());
  for (const auto& s : associations) {
    const auto& pa = a.source_patches[static_cast<std::size_t>(s.a)];
    const auto& pb = a.target_patches[static_cast<std::size_t>(s.b)];
    // A lower edit distance is more evidence: weight 1 - D_hat in [0, 1].
    out.push_back({pa.centroid, pa.normal.normalized(), pb.centroid, pb.normal.normalized(),
                   std::max(0.0, 1.0 - s.distance)});
  }
  return out;
}

/// RANSAC and the patch refinement on h.used.
void estimate(const AssociatedViews& a, const HypothesiseParams& params, Hypothesis& h) {
  h.correspondences = toCorrespondences(h.used, a);
  h.pose = estimatePose(h.correspondences, params.pose);
  h.ransac_ms += h.pose.ransac_ms;
  h.refine_ms += h.pose.refine_ms;
}

}  // namespace

void validate(const HypothesiseParams& p) {
  validate(p.pose);
  validate(p.guided.gates);
  if (p.guided.min_support < 3) throw Error("hypothesise: guided.min_support must be >= 3");
}

std::vector<PatchAssociation> guidedAt(const AssociatedViews& a, const Isometry3& T_target_source,
                                       const GuidedVerificationParams& params) {
  return guidedAssociations(a.source_patches, a.target_patches, a.source_features, a.target_features,
                            T_target_source, a.params, params.gates);
}

Hypothesis hypothesise(const AssociatedViews& a, std::vector<PatchAssociation> used, const HypothesiseParams& params) {
  Hypothesis h;
  h.used = std::move(used);
  estimate(a, params, h);
  if (!h.found()) return h;
  if (!params.guided.enabled) {
    h.verified = true;
    return h;
  }
  const auto t0 = std::chrono::steady_clock::now();
  h.guided = guidedAt(a, h.pose.T_target_source, params.guided);
  h.guided_ms += msSince(t0);
  h.guided_support = static_cast<int>(h.guided.size());
  if (h.guided_support < params.guided.min_support) {
    h.pose.success = false;
    h.pose.reason = "guided verification: " + std::to_string(h.guided_support) +
                    " source patches find a partner that agrees with the pose (min_support " +
                    std::to_string(params.guided.min_support) + ")";
    return h;
  }
  if (!params.guided.densify) {
    h.verified = true;
    return h;
  }
  h.used = h.guided;
  estimate(a, params, h);
  h.verified = h.found();
  if (!h.verified) h.pose.reason = "on the guided associations: " + h.pose.reason;
  return h;
}

}  // namespace gasp
