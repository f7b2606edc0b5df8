#include "gasp/core/pose_perturbation.h"

namespace gasp {

Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d S;
  S << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return S;
}

Isometry3 expLeft(const Vector6& xi) {
  Isometry3 T = Isometry3::Identity();
  const Eigen::Vector3d r = xi.tail<3>();
  if (r.norm() > 0.0) T.linear() = Eigen::AngleAxisd(r.norm(), r.normalized()).toRotationMatrix();
  T.translation() = xi.head<3>();
  return T;
}

Vector6 leftPerturbation(const Isometry3& T_a, const Isometry3& T_b) {
  const Isometry3 E = T_a * T_b.inverse();
  const Eigen::AngleAxisd aa(E.rotation());
  Vector6 xi;
  xi.head<3>() = E.translation();
  xi.tail<3>() = aa.angle() * aa.axis();
  return xi;
}

Matrix6 adjoint(const Isometry3& T) {
  const Eigen::Matrix3d R = T.rotation();
  Matrix6 Ad = Matrix6::Zero();
  Ad.topLeftCorner<3, 3>() = R;
  Ad.topRightCorner<3, 3>() = skew(T.translation()) * R;
  Ad.bottomRightCorner<3, 3>() = R;
  return Ad;
}

}  // namespace gasp
