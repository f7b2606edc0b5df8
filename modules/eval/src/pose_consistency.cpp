#include "gasp/eval/pose_consistency.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/LU>

#include <cmath>

#include "gasp/core/error.h"
#include "gasp/core/pose_perturbation.h"

namespace gasp::eval {

namespace {

/// Throws unless the information is finite, symmetric and positive semi-definite; returns its
/// eigenvalues (ascending).
Vector6 checkedEigenvalues(const Matrix6& information) {
  if (!information.allFinite()) throw Error("nees: the information matrix is not finite");
  const double scale = information.cwiseAbs().maxCoeff();
  if ((information - information.transpose()).cwiseAbs().maxCoeff() > 1e-9 * scale)
    throw Error("nees: the information matrix is not symmetric");
  const Eigen::SelfAdjointEigenSolver<Matrix6> eig(information, Eigen::EigenvaluesOnly);
  if (eig.eigenvalues()(0) < -1e-9 * scale) throw Error("nees: the information matrix is not positive semi-definite");
  return eig.eigenvalues();
}

}  // namespace

Vector6 leftPerturbation(const Isometry3& T_est, const Isometry3& T_ref) {
  const Isometry3 D = T_est * T_ref.inverse();
  const Eigen::AngleAxisd aa(D.linear());
  const double theta = aa.angle();
  const Eigen::Vector3d omega = theta * aa.axis();
  const Eigen::Matrix3d W = skew(omega);
  // V^-1 = I - W / 2 + c W^2, c = (1 - theta sin(theta) / (2 (1 - cos(theta)))) / theta^2
  // (-> 1/12 as theta -> 0).
  const double c = theta < 1e-4 ? 1.0 / 12.0 + theta * theta / 720.0
                                 : (1.0 - theta * std::sin(theta) / (2.0 * (1.0 - std::cos(theta)))) / (theta * theta);
  const Eigen::Matrix3d V_inv = Eigen::Matrix3d::Identity() - 0.5 * W + c * W * W;
  Vector6 xi;
  xi.head<3>() = V_inv * D.translation();
  xi.tail<3>() = omega;
  return xi;
}

double nees(const Isometry3& T_est, const Isometry3& T_ref, const Matrix6& information) {
  checkedEigenvalues(information);
  const Vector6 xi = leftPerturbation(T_est, T_ref);
  return xi.dot(information * xi);
}

NeesParts neesParts(const Isometry3& T_est, const Isometry3& T_ref, const Matrix6& information) {
  const Vector6 ev = checkedEigenvalues(information);
  if (!(ev(0) > 1e-12 * ev(5))) throw Error("nees: the information matrix is not invertible");
  const Vector6 xi = leftPerturbation(T_est, T_ref);
  const Matrix6 covariance = information.inverse();
  NeesParts p;
  p.all = xi.dot(information * xi);
  p.translation = xi.head<3>().dot(covariance.topLeftCorner<3, 3>().ldlt().solve(xi.head<3>()));
  p.rotation = xi.tail<3>().dot(covariance.bottomRightCorner<3, 3>().ldlt().solve(xi.tail<3>()));
  return p;
}

}  // namespace gasp::eval
