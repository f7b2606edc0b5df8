#pragma once
/// \file refinement.h Robust point-to-plane refinement of T_target_source.
///
/// With T = (R, t) and weights w, the residuals [m] are, for each patch correspondence,
///   forward:  r_f = n_t . (R p_s + t - p_t)            source centroid vs the target patch's plane
///   backward: r_b = n_s . (R^T (p_t - t) - p_s)        target centroid, mapped back, vs the source plane
/// (backward only when bidirectional), and for each dense term r_d = n . (R p + t - q). The
/// cost is 1/2 sum_i w_i rho(r_i^2) with rho the robust loss of scale a = loss_scale_m, w_i the
/// term's weight, halved for the two directions of a patch pair (both measure nearly the same
/// error, since n_t ~ R n_s, so together they count as one measurement):
///   Huber:  rho(s) = s for s <= a^2, 2 a sqrt(s) - a^2 beyond;   Cauchy: rho(s) = a^2 log(1 + s/a^2).
/// The pose lives on SO(3) x R^3: an Eigen quaternion with ceres::EigenQuaternionManifold
/// (q <- [cos|d|, sin|d| d/|d|] * q, a rotation by 2|d| on the left) and a Euclidean
/// translation. Levenberg-Marquardt on this cost, by one of two solvers (`solver`):
///   ceres:            ceres::Solver, one residual block per term, dense QR (the paper's);
///   normal_equations: the same Levenberg-Marquardt model (rows scaled by sqrt(w_i rho'(r_i^2)),
///                     which is Ceres' corrector for rho'' <= 0, as for Huber and Cauchy) built as
///                     the 6 x 6 normal equations over xi and solved in place, with Ceres' trust
///                     region rule and stopping tolerances. It reaches the same minimum without
///                     Ceres' per-block overhead: many times faster for thousands of dense terms.
///
/// Information: the Jacobian J of the residuals at the solution over the left perturbation
/// xi = [rho; omega] of registration_result.h, robustified (row i scaled by sqrt(w_i rho'(r_i^2)),
/// Ceres' corrector for rho'' <= 0), and I = J^T J / noise_sigma_m^2, whichever solver ran.
/// The degeneracy check (degeneracy.h) runs on I; a degenerate estimate is not claimed. With
/// partial_poses, an estimate with at most kMaxFreeDirections unobservable directions is a partial
/// one (partial_pose.h): the solve's step is kept in the observed directions only (solution
/// remapping, Zhang, Kaess & Singh, ICRA 2016), so the free directions stay where T_init had them.
#include <vector>

#include "gasp/core/pose.h"
#include "gasp/registration/correspondence.h"
#include "gasp/registration/degeneracy.h"
#include "gasp/registration/registration_result.h"

namespace gasp {

enum class RobustLoss { kNone, kHuber, kCauchy };
enum class PoseSolver { kCeres, kNormalEquations };

struct RefinementParams {
  RobustLoss loss = RobustLoss::kHuber;
  double loss_scale_m = 0.02;  ///< a, the robust loss's scale [m]
  bool bidirectional = true;   ///< also the backward residuals (target centroids vs source planes)
  int max_iterations = 50;     ///< Levenberg-Marquardt iterations; 0 evaluates at T_init only
  double noise_sigma_m = 0.01; ///< sigma of a point-to-plane residual, scales the information [m]
  DegeneracyParams degeneracy; ///< ratio 1e-2, max std 0.05 m
  bool partial_poses = false;  ///< a degenerate estimate may be a partial pose (above)
  PoseSolver solver = PoseSolver::kNormalEquations;  ///< who solves (above); the same cost and minimum
};

/// Throws gasp::Error naming the first invalid parameter.
void validate(const RefinementParams& params);

/// The weight the solver's robust loss gives a term of residual `residual_m` [m]: rho'(r^2) of
/// params.loss at params.loss_scale_m, as Ceres' HuberLoss and CauchyLoss compute it (1 within
/// Huber's scale and without a loss).
double robustWeight(const RefinementParams& params, double residual_m);

/// Refines T_init on all the given patch correspondences (their indices are the result's
/// inliers) and the optional dense terms; either list may be empty, not both. Invalid input or
/// a failed solve gives success = false with a reason; never throws for data.
RegistrationResult refinePose(const std::vector<PatchCorrespondence>& correspondences, const Isometry3& T_init,
                              const RefinementParams& params = {}, const std::vector<PointToPlane>& dense = {});

}  // namespace gasp
