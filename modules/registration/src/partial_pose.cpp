#include "gasp/registration/partial_pose.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/QR>

#include <algorithm>
#include <cmath>

#include "gasp/core/error.h"
#include "gasp/core/pose_perturbation.h"

namespace gasp {
namespace {

Matrix6d conditioning(const RegistrationResult& r) { return gasp::conditioning(r.scene_centre, r.scene_radius_m); }

/// I - U U^T in the conditioned coordinates.
Matrix6d observedConditioned(const RegistrationResult& r) {
  const auto& U = r.unobservable_directions;
  return Matrix6d::Identity() - U * U.transpose();
}

}  // namespace

Matrix6d observedProjector(const RegistrationResult& r) {
  if (r.unobservable_directions.cols() == 0) return Matrix6d::Identity();
  const Matrix6d BS = conditioning(r);
  return BS * observedConditioned(r) * BS.inverse();
}

Matrix6d observedInformation(const RegistrationResult& r, const Matrix6d& information) {
  const Matrix6d Pi = observedProjector(r);
  const Matrix6d I = Pi.transpose() * information * Pi;
  return 0.5 * (I + I.transpose());
}

Matrix6d observedInformationWithCovariance(const RegistrationResult& r, const Matrix6d& information,
                                           const Matrix6d& added_covariance) {
  if (!information.allFinite() || !added_covariance.allFinite())
    throw Error("observed information: the information or the added covariance is not finite");
  const Matrix6d BS = conditioning(r), to_conditioned = BS.inverse();
  const auto& U = r.unobservable_directions;
  // Q: the orthonormal complement of U (the last columns of a full QR of U).
  Eigen::MatrixXd Q = Eigen::MatrixXd::Identity(6, 6);
  if (U.cols() > 0) Q = Eigen::HouseholderQR<Eigen::MatrixXd>(U).householderQ() * Eigen::MatrixXd::Identity(6, 6);
  Q = Q.rightCols(6 - U.cols()).eval();
  const Eigen::MatrixXd Ic = BS.transpose() * information * BS;
  const Eigen::MatrixXd Cc = to_conditioned * added_covariance * to_conditioned.transpose();
  // The observed directions' marginal: the free ones are unknown, so what the information says
  // about them is taken out (Schur complement; a pseudo-inverse, as they may carry none).
  Eigen::MatrixXd Iq = Q.transpose() * Ic * Q;
  if (U.cols() > 0) {
    const Eigen::MatrixXd Iff = U.transpose() * Ic * U, Iqf = Q.transpose() * Ic * U;
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(0.5 * (Iff + Iff.transpose()));
    const double tiny = 1e-12 * std::max(1.0, eig.eigenvalues().cwiseAbs().maxCoeff());
    Eigen::VectorXd inv = eig.eigenvalues();
    for (Eigen::Index k = 0; k < inv.size(); ++k) inv(k) = inv(k) > tiny ? 1.0 / inv(k) : 0.0;
    Iq -= Iqf * eig.eigenvectors() * inv.asDiagonal() * eig.eigenvectors().transpose() * Iqf.transpose();
  }
  const Eigen::LLT<Eigen::MatrixXd> llt(0.5 * (Iq + Iq.transpose()));
  if (llt.info() != Eigen::Success)
    throw Error("observed information: the information is not positive definite in the observed directions");
  const auto m = Q.cols();
  Eigen::MatrixXd Cq = llt.solve(Eigen::MatrixXd::Identity(m, m)) + Q.transpose() * Cc * Q;
  Cq = 0.5 * (Cq + Cq.transpose());
  const Eigen::LLT<Eigen::MatrixXd> llt_c(Cq);
  if (llt_c.info() != Eigen::Success) throw Error("observed information: the covariance is not positive definite");
  const Eigen::MatrixXd Ic_obs = Q * llt_c.solve(Eigen::MatrixXd::Identity(m, m)) * Q.transpose();
  const Matrix6d I = to_conditioned.transpose() * Ic_obs * to_conditioned;
  return 0.5 * (I + I.transpose());
}

Eigen::Matrix<double, 6, Eigen::Dynamic> unobservableTwists(const RegistrationResult& r) {
  return conditioning(r) * r.unobservable_directions;
}

Eigen::Matrix<double, 6, Eigen::Dynamic> unitedDirections(const RegistrationResult& r,
                                                          const Eigen::Matrix<double, 6, Eigen::Dynamic>& more) {
  // The sum of the directions' projectors, S = U U^T + sum d d^T (unit d, conditioned): two unit
  // directions at an angle theta give the eigenvalues 1 +- cos(theta), so the eigenvectors above
  // 1 - cos(kSameDirectionDeg) span every direction that is not a near copy of another -- also
  // where one analysis finds a mixture of two directions the other finds apart.
  const Eigen::Matrix<double, 6, Eigen::Dynamic>& U = r.unobservable_directions;
  if (more.cols() == 0) return U;
  const Matrix6d to_conditioned = conditioning(r).inverse();
  Matrix6d S = U * U.transpose();
  for (Eigen::Index j = 0; j < more.cols(); ++j) {
    const Vector6d d = to_conditioned * more.col(j);
    if (d.allFinite() && d.norm() > 0.0) S += d.normalized() * d.normalized().transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Matrix6d> eig(S);
  const double floor = 1.0 - std::cos(kSameDirectionDeg * M_PI / 180.0);
  int k = 0;
  while (k < 6 && eig.eigenvalues()(5 - k) > floor) ++k;
  return eig.eigenvectors().rightCols(k).rowwise().reverse();
}

ObservedError observedError(const RegistrationResult& r, const Isometry3& T_true) {
  const Vector6d xi = leftPerturbation(r.T_target_source, T_true);
  Vector6d e = conditioning(r).inverse() * xi;
  if (r.unobservable_directions.cols() > 0) e = observedConditioned(r) * e;
  ObservedError out;
  out.translation_m = e.head<3>().norm();
  out.rotation_deg = e.tail<3>().norm() / std::max(r.scene_radius_m, kMinSceneRadiusM) * 180.0 / M_PI;
  return out;
}

Isometry3 withPrediction(const RegistrationResult& r, const Isometry3& predicted) {
  if (r.unobservable_directions.cols() == 0) return r.T_target_source;
  const Matrix6d free = Matrix6d::Identity() - observedProjector(r);
  // Each move is along the free directions only; repeated, the first-order move converges onto
  // the prediction's free components.
  Isometry3 T = r.T_target_source;
  for (int k = 0; k < 3; ++k) T = expLeft(free * leftPerturbation(predicted, T)) * T;
  return T;
}

}  // namespace gasp
