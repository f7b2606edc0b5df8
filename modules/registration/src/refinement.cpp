#include "gasp/registration/refinement.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "gasp/core/error.h"
#include "gasp/core/pose_perturbation.h"
#include "gasp/core/stopwatch.h"
#include "gasp/registration/partial_pose.h"
#include "pose_problem.h"

namespace gasp {
namespace {

void residualStatistics(std::vector<double> r, RegistrationResult& out) {
  out.num_residuals = static_cast<int>(r.size());
  if (r.empty()) return;
  double sq = 0.0;
  for (double& v : r) {
    sq += v * v;
    v = std::abs(v);
  }
  out.rms_residual_m = std::sqrt(sq / static_cast<double>(r.size()));
  const auto mid = r.begin() + static_cast<std::ptrdiff_t>(r.size() / 2);
  std::nth_element(r.begin(), mid, r.end());
  out.median_residual_m = *mid;
  if (r.size() % 2 == 0) out.median_residual_m = 0.5 * (*mid + *std::max_element(r.begin(), mid));
}

}  // namespace

void validate(const RefinementParams& params) {
  if (!(params.loss_scale_m > 0.0) || !std::isfinite(params.loss_scale_m))
    throw Error("RefinementParams.loss_scale_m must be positive and finite");
  if (params.max_iterations < 0) throw Error("RefinementParams.max_iterations must be >= 0");
  if (!(params.noise_sigma_m > 0.0) || !std::isfinite(params.noise_sigma_m))
    throw Error("RefinementParams.noise_sigma_m must be positive and finite");
  validate(params.degeneracy);
}

RegistrationResult refinePose(const std::vector<PatchCorrespondence>& correspondences, const Isometry3& T_init,
                              const RefinementParams& params, const std::vector<PointToPlane>& dense) {
  validate(params);
  const auto start = std::chrono::steady_clock::now();
  RegistrationResult out;
  out.T_target_source = T_init;
  std::string why = invalidInput(correspondences);
  if (why.empty()) why = invalidInput(dense);
  if (why.empty() && !T_init.matrix().allFinite()) why = "T_init is not finite";
  if (!why.empty()) {
    out.reason = "invalid input: " + why;
    return out;
  }

  detail::PoseProblem problem(T_init, params);
  problem.reserve((params.bidirectional ? 2 : 1) * correspondences.size() + dense.size());
  for (const auto& c : correspondences) problem.addPatch(c);
  for (const auto& d : dense) problem.addDense(d);
  if (problem.numResiduals() == 0) {
    out.reason = "no residuals (no correspondences or dense terms with a positive weight)";
    return out;
  }
  if (params.max_iterations > 0) {
    const detail::PoseSolve solve = problem.solve();
    out.iterations = solve.iterations;
    if (!solve.usable) {
      out.reason = std::string(params.solver == PoseSolver::kCeres ? "Ceres" : "the solve") + " failed: " + solve.message;
      return out;
    }
  }
  out.T_target_source = problem.pose();
  for (int i = 0; i < static_cast<int>(correspondences.size()); ++i) out.inliers.push_back(i);
  out.num_inliers = static_cast<int>(out.inliers.size());
  residualStatistics(problem.residuals(), out);

  const auto analyse = [&] {
    out.information = problem.information();
    problem.sceneExtent(out.scene_centre, out.scene_radius_m);
    DegeneracyAnalysis analysis =
        analyseDegeneracy(out.information, out.scene_centre, out.scene_radius_m, params.degeneracy);
    out.information_eigenvalues = analysis.eigenvalues;
    out.degenerate = analysis.degenerate;
    out.unobservable_directions = std::move(analysis.unobservable_directions);
    out.reason = std::move(analysis.reason);
  };
  analyse();
  out.success = !out.degenerate;
  out.partial = params.partial_poses && out.degenerate && out.unobservable_directions.cols() <= kMaxFreeDirections;
  if (out.partial && params.max_iterations > 0) {
    // The step along the free directions is noise: back to T_init there, along them only, so the
    // observed directions keep the solve's optimum.
    const Isometry3 remapped = withPrediction(out, T_init);
    problem.setPose(remapped);
    out.T_target_source = remapped;
    residualStatistics(problem.residuals(), out);
    analyse();
    out.success = !out.degenerate;
    out.partial = out.degenerate && out.unobservable_directions.cols() <= kMaxFreeDirections;
  }
  out.refine_ms = msSince(start);
  return out;
}

}  // namespace gasp
