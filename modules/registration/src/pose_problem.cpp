#include "pose_problem.h"

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>

#include "gasp/core/error.h"
#include "gasp/core/pose_perturbation.h"
#include "plane_residuals.h"

namespace gasp::detail {
namespace {

std::unique_ptr<ceres::LossFunction> makeLoss(const RefinementParams& params) {
  switch (params.loss) {
    case RobustLoss::kHuber: return std::make_unique<ceres::HuberLoss>(params.loss_scale_m);
    case RobustLoss::kCauchy: return std::make_unique<ceres::CauchyLoss>(params.loss_scale_m);
    case RobustLoss::kNone: break;
  }
  return nullptr;
}

/// rho(s) and rho'(s) of the robust loss at s = r^2, as Ceres' HuberLoss and CauchyLoss compute them.
void robust(const RefinementParams& params, double s, double& rho, double& rho1) {
  const double a = params.loss_scale_m, b = a * a;
  switch (params.loss) {
    case RobustLoss::kHuber:
      if (s > b) {
        const double r = std::sqrt(s);
        rho = 2.0 * a * r - b;
        rho1 = std::max(std::numeric_limits<double>::min(), a / r);
        return;
      }
      break;
    case RobustLoss::kCauchy: {
      const double sum = 1.0 + s / b;
      rho = b * std::log(sum);
      rho1 = std::max(std::numeric_limits<double>::min(), 1.0 / sum);
      return;
    }
    case RobustLoss::kNone: break;
  }
  rho = s;
  rho1 = 1.0;
}

// Ceres' defaults and the tolerances this problem always used (Solver::Options).
constexpr double kFunctionTolerance = 1e-10;
constexpr double kGradientTolerance = 1e-14;
constexpr double kParameterTolerance = 1e-9;
constexpr double kInitialRadius = 1e4, kMaxRadius = 1e16, kMinRadius = 1e-32;
constexpr double kMinLmDiagonal = 1e-6, kMaxLmDiagonal = 1e32;
constexpr double kMinRelativeDecrease = 1e-3;

}  // namespace

PoseProblem::PoseProblem(const Isometry3& T_init, const RefinementParams& params) : params_(params) { setPose(T_init); }

void PoseProblem::setPose(const Isometry3& T) {
  T_ = Isometry3::Identity();
  T_.linear() = Eigen::Quaterniond(T.rotation()).normalized().toRotationMatrix();
  T_.translation() = T.translation();
}

void PoseProblem::add(const Term& term) {
  if (term.weight > 0.0) terms_.push_back(term);
}

void PoseProblem::addPatch(const PatchCorrespondence& c) {
  // Both directions measure nearly the same error (n_t ~ R n_s): half weight each, so that a
  // patch pair counts as one measurement in the information.
  const double w = params_.bidirectional ? 0.5 * c.weight : c.weight;
  add({c.p_source, c.p_target, c.n_target, w, false});
  if (params_.bidirectional) add({c.p_source, c.p_target, c.n_source, w, true});
}

void PoseProblem::addDense(const PointToPlane& term) {
  add({term.p_source, term.q_target, term.n_target, term.weight, false});
}

PoseProblem::Linearised PoseProblem::linearise(const Term& term, const Isometry3& T) const {
  // Under T <- Exp(xi) T a target-frame point x moves by rho + omega x x.
  Linearised l;
  if (!term.backward) {
    const Eigen::Vector3d x = T * term.a;
    l.r = term.n.dot(x - term.b);
    l.J << term.n, x.cross(term.n);
  } else {  // r = m . (b - t) - n . a with m = R n
    const Eigen::Vector3d m = T.linear() * term.n;
    l.r = m.dot(term.b - T.translation()) - term.n.dot(term.a);
    l.J << -m, m.cross(term.b);
  }
  robust(params_, l.r * l.r, l.rho, l.rho1);
  l.rho *= term.weight;
  l.rho1 *= term.weight;
  return l;
}

PoseSolve PoseProblem::solve() {
  return params_.solver == PoseSolver::kCeres ? solveByCeres() : solveByNormalEquations();
}

PoseSolve PoseProblem::solveByCeres() {
  ceres::Problem::Options problem_options;
  problem_options.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  problem_options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  problem_options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  const std::unique_ptr<ceres::LossFunction> loss = makeLoss(params_);
  ceres::EigenQuaternionManifold quaternion_manifold;
  std::vector<std::unique_ptr<ceres::LossFunction>> scaled_losses;
  std::vector<std::unique_ptr<ceres::CostFunction>> costs;
  costs.reserve(terms_.size());
  Eigen::Quaterniond q(T_.rotation());
  Eigen::Vector3d t = T_.translation();
  PoseSolve out;
  {
    ceres::Problem problem(problem_options);  // destroyed before what it borrows
    problem.AddParameterBlock(q.coeffs().data(), 4, &quaternion_manifold);
    problem.AddParameterBlock(t.data(), 3);
    for (const Term& term : terms_) {
      ceres::LossFunction* l = loss.get();
      if (term.weight != 1.0) {  // w rho(s): the weight leaves the loss's scale in metres
        scaled_losses.push_back(std::make_unique<ceres::ScaledLoss>(loss.get(), term.weight, ceres::DO_NOT_TAKE_OWNERSHIP));
        l = scaled_losses.back().get();
      }
      if (term.backward)
        costs.push_back(std::make_unique<SourcePlaneCost>(SourcePlaneResidual{term.a, term.n, term.b}));
      else
        costs.push_back(std::make_unique<TargetPlaneCost>(TargetPlaneResidual{term.a, term.b, term.n}));
      problem.AddResidualBlock(costs.back().get(), l, q.coeffs().data(), t.data());
    }
    ceres::Solver::Options options;
    options.linear_solver_type = ceres::DENSE_QR;
    options.max_num_iterations = params_.max_iterations;
    options.function_tolerance = kFunctionTolerance;
    options.gradient_tolerance = kGradientTolerance;
    options.parameter_tolerance = kParameterTolerance;
    options.num_threads = 1;
    options.logging_type = ceres::SILENT;
    ceres::Solver::Summary summary;
    ceres::Solve(options, &problem, &summary);
    out.iterations = summary.num_successful_steps + summary.num_unsuccessful_steps;
    out.usable = summary.IsSolutionUsable();
    out.message = summary.message;
    if (!out.usable) return out;
  }
  T_.linear() = q.normalized().toRotationMatrix();
  T_.translation() = t;
  return out;
}

namespace {

/// The normal equations' sums over a range of terms: H's lower triangle by columns (21 entries).
struct EquationSums {
  double cost = 0.0;
  std::array<double, 21> lower{};
  Vector6d g = Vector6d::Zero();
  void join(const EquationSums& o) {
    cost += o.cost;
    for (std::size_t k = 0; k < lower.size(); ++k) lower[k] += o.lower[k];
    g += o.g;
  }
};

/// Terms per task of the normal equations' sums; fewer terms are summed in one pass. The split
/// depends on the number of terms alone, so the sums are the same on any number of threads.
constexpr std::size_t kTermsPerTask = 2048;

}  // namespace

PoseProblem::NormalEquations PoseProblem::equationsAt(const Isometry3& T) const {
  const auto sum = [&](std::size_t begin, std::size_t end, EquationSums s) {
    for (std::size_t i = begin; i < end; ++i) {
      const Linearised l = linearise(terms_[i], T);
      s.cost += 0.5 * l.rho;
      const Vector6d wJ = l.rho1 * l.J;
      std::size_t k = 0;
      for (int c = 0; c < 6; ++c)
        for (int r = c; r < 6; ++r) s.lower[k++] += wJ(r) * l.J(c);
      s.g += l.r * wJ;
    }
    return s;
  };
  EquationSums total;
  if (terms_.size() <= kTermsPerTask) {
    total = sum(0, terms_.size(), EquationSums{});
  } else {
    total = tbb::parallel_deterministic_reduce(
        tbb::blocked_range<std::size_t>(0, terms_.size(), kTermsPerTask), EquationSums{},
        [&](const tbb::blocked_range<std::size_t>& range, EquationSums s) { return sum(range.begin(), range.end(), s); },
        [](EquationSums a, const EquationSums& b) {
          a.join(b);
          return a;
        });
  }
  NormalEquations e;
  e.cost = total.cost;
  e.g = total.g;
  std::size_t k = 0;
  for (int c = 0; c < 6; ++c)
    for (int r = c; r < 6; ++r) e.H(r, c) = e.H(c, r) = total.lower[k++];
  return e;
}

PoseSolve PoseProblem::solveByNormalEquations() {
  PoseSolve out;
  NormalEquations here = equationsAt(T_);
  if (!std::isfinite(here.cost)) {
    out.usable = false;
    out.message = "the cost at the start is not finite";
    return out;
  }
  double radius = kInitialRadius, decrease_factor = 2.0;
  // Ceres' Levenberg-Marquardt: (H + D / radius) step = -g, D the clamped diagonal of H; a step
  // is taken when the cost falls by at least a share of the model's predicted decrease.
  for (int iteration = 0; iteration < params_.max_iterations; ++iteration) {
    if (here.g.lpNorm<Eigen::Infinity>() <= kGradientTolerance) break;
    Matrix6d A = here.H;
    for (int i = 0; i < 6; ++i) A(i, i) += std::clamp(here.H(i, i), kMinLmDiagonal, kMaxLmDiagonal) / radius;
    const Vector6d step = A.ldlt().solve(-here.g);
    ++out.iterations;
    const double x_norm = std::sqrt(1.0 + T_.translation().squaredNorm());  // |(q, t)|, q a unit quaternion
    if (step.allFinite() && step.norm() <= kParameterTolerance * (x_norm + kParameterTolerance)) break;
    const double model_decrease = -(here.g.dot(step) + 0.5 * step.dot(here.H * step));
    bool taken = false;
    if (step.allFinite() && model_decrease > 0.0) {
      const Isometry3 T_next = expLeft(step) * T_;
      NormalEquations there = equationsAt(T_next);
      const double relative_decrease = (here.cost - there.cost) / model_decrease;
      if (std::isfinite(there.cost) && relative_decrease > kMinRelativeDecrease) {
        taken = true;
        const double function_change = here.cost - there.cost;
        const double cost_before = here.cost;
        setPose(T_next);
        here = std::move(there);
        radius = std::min(kMaxRadius, radius / std::max(1.0 / 3.0, 1.0 - std::pow(2.0 * relative_decrease - 1.0, 3)));
        decrease_factor = 2.0;
        if (std::abs(function_change) <= kFunctionTolerance * cost_before) break;
      }
    }
    if (!taken) {
      radius /= decrease_factor;
      decrease_factor *= 2.0;
      if (radius < kMinRadius) break;
    }
  }
  return out;
}

std::vector<double> PoseProblem::residuals() const {
  std::vector<double> r;
  r.reserve(terms_.size());
  for (const Term& term : terms_) r.push_back(linearise(term, T_).r);
  return r;
}

Matrix6d PoseProblem::information() const {
  // H of the normal equations is the robustified J^T J.
  const Matrix6d information = equationsAt(T_).H / (params_.noise_sigma_m * params_.noise_sigma_m);
  return 0.5 * (information + information.transpose());
}

void PoseProblem::sceneExtent(Eigen::Vector3d& centre, double& radius_m) const {
  // A term's point in the target frame: the mapped source point, or the target point.
  const auto pointOf = [this](const Term& term) { return term.backward ? term.b : Eigen::Vector3d(T_ * term.a); };
  centre.setZero();
  double sum = 0.0;
  for (const Term& term : terms_) {
    centre += term.weight * pointOf(term);
    sum += term.weight;
  }
  if (!(sum > 0.0)) {
    radius_m = 0.0;
    return;
  }
  centre /= sum;
  double sq = 0.0;
  for (const Term& term : terms_) sq += term.weight * (pointOf(term) - centre).squaredNorm();
  radius_m = std::sqrt(sq / sum);
}

}  // namespace gasp::detail

namespace gasp {

double robustWeight(const RefinementParams& params, double residual_m) {
  double rho = 0.0, rho1 = 0.0;
  detail::robust(params, residual_m * residual_m, rho, rho1);
  return rho1;
}

}  // namespace gasp
