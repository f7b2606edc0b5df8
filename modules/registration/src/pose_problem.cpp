#include "pose_problem.h"

#include <Eigen/Geometry>

#include <cmath>

#include "gasp/core/error.h"
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

ceres::Problem::Options borrowingOptions() {
  ceres::Problem::Options options;
  options.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  return options;
}

}  // namespace

PoseProblem::PoseProblem(const Isometry3& T_init, const RefinementParams& params)
    : params_(params),
      loss_(makeLoss(params)),
      quaternion_manifold_(std::make_unique<ceres::EigenQuaternionManifold>()),
      problem_(borrowingOptions()) {
  const Eigen::Quaterniond q(T_init.rotation());
  Eigen::Map<Eigen::Quaterniond>(q_.data()) = q.normalized();
  Eigen::Map<Eigen::Vector3d>(t_.data()) = T_init.translation();
  problem_.AddParameterBlock(q_.data(), 4, quaternion_manifold_.get());
  problem_.AddParameterBlock(t_.data(), 3);
}

void PoseProblem::add(std::unique_ptr<ceres::CostFunction> cost, double weight, const TermPoint& where) {
  if (!(weight > 0.0)) return;
  ceres::LossFunction* loss = loss_.get();
  if (weight != 1.0) {  // w rho(s): the weight leaves the loss's scale in metres
    scaled_losses_.push_back(std::make_unique<ceres::ScaledLoss>(loss_.get(), weight, ceres::DO_NOT_TAKE_OWNERSHIP));
    loss = scaled_losses_.back().get();
  }
  problem_.AddResidualBlock(cost.get(), loss, q_.data(), t_.data());
  costs_.push_back(std::move(cost));
  points_.push_back(where);
}

void PoseProblem::addPatch(const PatchCorrespondence& c) {
  // Both directions measure nearly the same error (n_t ~ R n_s): half weight each, so that a
  // patch pair counts as one measurement in the information.
  const double w = params_.bidirectional ? 0.5 * c.weight : c.weight;
  add(std::make_unique<TargetPlaneCost>(TargetPlaneResidual{c.p_source, c.p_target, c.n_target}), w, {c.p_source, true, w});
  if (params_.bidirectional)
    add(std::make_unique<SourcePlaneCost>(SourcePlaneResidual{c.p_source, c.n_source, c.p_target}), w,
        {c.p_target, false, w});
}

void PoseProblem::addDense(const PointToPlane& term) {
  add(std::make_unique<TargetPlaneCost>(TargetPlaneResidual{term.p_source, term.q_target, term.n_target}), term.weight,
      {term.p_source, true, term.weight});
}

ceres::Solver::Summary PoseProblem::solve() {
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::DENSE_QR;
  options.max_num_iterations = params_.max_iterations;
  options.function_tolerance = 1e-10;
  options.gradient_tolerance = 1e-14;
  options.parameter_tolerance = 1e-9;
  options.num_threads = 1;
  options.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem_, &summary);
  return summary;
}

Isometry3 PoseProblem::pose() const {
  Isometry3 T = Isometry3::Identity();
  T.linear() = Eigen::Map<const Eigen::Quaterniond>(q_.data()).normalized().toRotationMatrix();
  T.translation() = Eigen::Map<const Eigen::Vector3d>(t_.data());
  return T;
}

void PoseProblem::setPose(const Isometry3& T) {
  Eigen::Map<Eigen::Quaterniond>(q_.data()) = Eigen::Quaterniond(T.rotation()).normalized();
  Eigen::Map<Eigen::Vector3d>(t_.data()) = T.translation();
}

std::vector<double> PoseProblem::residuals() {
  ceres::Problem::EvaluateOptions options;
  options.apply_loss_function = false;
  std::vector<double> r;
  problem_.Evaluate(options, nullptr, &r, nullptr, nullptr);
  return r;
}

Matrix6d PoseProblem::information() {
  ceres::Problem::EvaluateOptions options;
  options.parameter_blocks = {q_.data(), t_.data()};  // columns: quaternion tangent d, then tau
  options.apply_loss_function = true;
  ceres::CRSMatrix crs;
  if (!problem_.Evaluate(options, nullptr, nullptr, nullptr, &crs))
    throw Error("Ceres could not evaluate the Jacobian");
  Matrix6d JtJ = Matrix6d::Zero();
  for (int row = 0; row < crs.num_rows; ++row) {
    Vector6d j = Vector6d::Zero();
    for (int k = crs.rows[row]; k < crs.rows[row + 1]; ++k) j(crs.cols[k]) = crs.values[k];
    JtJ += j * j.transpose();
  }
  // Ceres' tangent [d; tau] from xi = [rho; omega]: q <- Exp(2 d) q and t <- t + tau, while
  // Exp(xi) T gives R <- Exp(omega) R and t <- t + omega x t + rho, so d = omega / 2 and
  // tau = rho - [t]x omega.
  Matrix6d A = Matrix6d::Zero();
  A.topRightCorner<3, 3>() = 0.5 * Eigen::Matrix3d::Identity();
  A.bottomLeftCorner<3, 3>() = Eigen::Matrix3d::Identity();
  A.bottomRightCorner<3, 3>() = -plane_residuals::skew(Eigen::Map<const Eigen::Vector3d>(t_.data()));
  const Matrix6d information = A.transpose() * JtJ * A / (params_.noise_sigma_m * params_.noise_sigma_m);
  return 0.5 * (information + information.transpose());
}

void PoseProblem::sceneExtent(Eigen::Vector3d& centre, double& radius_m) const {
  const Isometry3 T = pose();
  centre.setZero();
  double sum = 0.0;
  for (const auto& p : points_) {
    centre += p.weight * (p.mapped ? T * p.point : p.point);
    sum += p.weight;
  }
  if (!(sum > 0.0)) {
    radius_m = 0.0;
    return;
  }
  centre /= sum;
  double sq = 0.0;
  for (const auto& p : points_) sq += p.weight * ((p.mapped ? T * p.point : p.point) - centre).squaredNorm();
  radius_m = std::sqrt(sq / sum);
}

}  // namespace gasp::detail
