#include "gasp/mrpt/pose_covariance.h"

#include <mrpt/math/wrap2pi.h>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <cmath>

#include "gasp/core/error.h"
#include "gasp/rawlog/observation_conversion.h"

namespace gasp {

namespace {

/// [x y z yaw pitch roll] of T.
Eigen::Matrix<double, 6, 1> ypr(const Isometry3& T) {
  const mrpt::poses::CPose3D p = toCPose3D(T);
  Eigen::Matrix<double, 6, 1> v;
  v << p.x(), p.y(), p.z(), p.yaw(), p.pitch(), p.roll();
  return v;
}

}  // namespace

Matrix6 informationInFrame(const Matrix6& information_ca, const Isometry3& S_a) {
  const Matrix6 Ad_inv = adjoint(S_a.inverse());
  return Ad_inv.transpose() * information_ca * Ad_inv;
}

Matrix6 yprJacobian(const Isometry3& T) {
  constexpr double h = 1e-6;
  Matrix6 J;
  for (int k = 0; k < 6; ++k) {
    Eigen::Matrix<double, 6, 1> xi = Eigen::Matrix<double, 6, 1>::Zero();
    xi[k] = h;
    Eigen::Matrix<double, 6, 1> d = ypr(expLeft(xi) * T) - ypr(expLeft(-xi) * T);
    for (int i = 3; i < 6; ++i) d[i] = mrpt::math::wrapToPi(d[i]);
    J.col(k) = d / (2 * h);
  }
  return J;
}

std::optional<mrpt::poses::CPose3DPDFGaussian> poseWithInformation(const Isometry3& T, const Matrix6& information) {
  if (!information.allFinite()) return std::nullopt;
  const Matrix6 I = 0.5 * (information + information.transpose());
  if (!I.isApprox(information, 1e-6) && (I - information).norm() > 1e-9 * (1.0 + I.norm())) return std::nullopt;
  const Eigen::LDLT<Matrix6> ldlt(I);
  if (ldlt.info() != Eigen::Success || !ldlt.isPositive() || (ldlt.vectorD().array() <= 0).any()) return std::nullopt;
  const Matrix6 cov_xi = ldlt.solve(Matrix6::Identity());
  if (!cov_xi.allFinite()) return std::nullopt;
  const Matrix6 J = yprJacobian(T);
  Matrix6 cov = J * cov_xi * J.transpose();
  cov = 0.5 * (cov + cov.transpose());
  mrpt::math::CMatrixDouble66 c;
  for (int r = 0; r < 6; ++r)
    for (int k = 0; k < 6; ++k) c(r, k) = cov(r, k);
  return mrpt::poses::CPose3DPDFGaussian(toCPose3D(T), c);
}

mrpt::poses::CPose3DPDFGaussian poseWithCovariance(const Isometry3& T, const Matrix6& covariance) {
  if (!covariance.allFinite() || (covariance - covariance.transpose()).norm() > 1e-9 * (1.0 + covariance.norm()))
    throw Error("pose covariance: not finite or not symmetric");
  const Matrix6 J = yprJacobian(T);
  Matrix6 cov = J * covariance * J.transpose();
  cov = 0.5 * (cov + cov.transpose());
  if (!cov.allFinite()) throw Error("pose covariance: no [x y z yaw pitch roll] covariance at pitch +-90 deg (gimbal lock)");
  mrpt::math::CMatrixDouble66 c;
  for (int r = 0; r < 6; ++r)
    for (int k = 0; k < 6; ++k) c(r, k) = cov(r, k);
  return mrpt::poses::CPose3DPDFGaussian(toCPose3D(T), c);
}

}  // namespace gasp
