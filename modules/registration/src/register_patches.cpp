#include "gasp/registration/register_patches.h"

#include <chrono>

#include "gasp/core/error.h"
#include "gasp/core/stopwatch.h"
#include "gasp/registration/inlier_criterion.h"

namespace gasp {
namespace {

using Clock = std::chrono::steady_clock;

std::vector<PatchCorrespondence> subset(const std::vector<PatchCorrespondence>& c, const std::vector<int>& indices) {
  std::vector<PatchCorrespondence> out;
  out.reserve(indices.size());
  for (int i : indices) out.push_back(c[i]);
  return out;
}

}  // namespace

void validate(const PoseEstimationParams& params) {
  validate(params.ransac);
  validate(params.refinement);
  if (params.reselection_rounds < 0) throw Error("PoseEstimationParams.reselection_rounds must be >= 0");
}

RegistrationResult estimatePose(const std::vector<PatchCorrespondence>& correspondences,
                                const PoseEstimationParams& params, const std::vector<PointToPlane>& dense) {
  validate(params);
  const auto ransac_start = Clock::now();
  const RansacResult ransac = ransacPose(correspondences, params.ransac);
  const double ransac_ms = msSince(ransac_start);

  RegistrationResult out;
  if (ransac.success) {
    const auto refine_start = Clock::now();
    RefinementParams refinement = params.refinement;
    if (!params.refine) refinement.max_iterations = 0;  // evaluate the RANSAC pose only
    const int rounds = params.refine ? 1 + params.reselection_rounds : 1;
    std::vector<int> inliers = ransac.inliers;
    Isometry3 T = ransac.T_target_source;
    int iterations = 0;
    for (int round = 0; round < rounds; ++round) {
      out = refinePose(subset(correspondences, inliers), T, refinement, dense);
      out.inliers = inliers;
      iterations += out.iterations;
      if (!out.success) break;  // degenerate (no better with other inliers), or a failed solve
      T = out.T_target_source;
      std::vector<int> reselected = selectInliers(correspondences, T, params.ransac.inlier);
      if (reselected == inliers || static_cast<int>(reselected.size()) < params.ransac.min_inliers) break;
      inliers = std::move(reselected);
    }
    out.iterations = iterations;
    out.refine_ms = msSince(refine_start);
  } else {
    out.T_target_source = ransac.T_target_source;
    out.reason = "RANSAC: " + ransac.reason;
  }
  out.num_inliers = static_cast<int>(out.inliers.size());
  out.alternative_T_target_source = ransac.alternative_T_target_source;
  out.alternative_inliers = ransac.alternative_inliers;
  out.ransac_iterations = ransac.iterations;
  out.ransac_ms = ransac_ms;
  return out;
}

}  // namespace gasp
