#include "gasp/core/pose.h"

#include <algorithm>
#include <cmath>


#include "gasp/core/error.h"

namespace gasp {

Isometry3 poseFromTranslationQuaternion(double tx, double ty, double tz, double qx, double qy,
                                        double qz, double qw) {
  Eigen::Quaterniond q(qw, qx, qy, qz);
  const double n = q.norm();
  if (!std::isfinite(n) || n < 1e-9) throw Error("quaternion is zero or not finite");
  q.coeffs() /= n;
  Isometry3 T = Isometry3::Identity();
  T.linear() = q.toRotationMatrix();
  T.translation() = Eigen::Vector3d(tx, ty, tz);
  return T;
}

double rotationAngle(const Isometry3& T) {
  const double c = (T.linear().trace() - 1.0) / 2.0;
  return std::acos(std::clamp(c, -1.0, 1.0));
}

PointSpread pointSpread(const std::vector<Eigen::Vector3d>& points) {
  PointSpread s;
  if (points.empty()) return s;
  for (const auto& p : points) s.mean += p;
  s.mean /= static_cast<double>(points.size());
  for (const auto& p : points) s.covariance += (p - s.mean) * (p - s.mean).transpose();
  s.covariance /= static_cast<double>(points.size());
  return s;
}

double rmsDisplacement(const Isometry3& T_a, const Isometry3& T_b, const PointSpread& points) {
  const Eigen::Matrix3d D = T_a.linear() - T_b.linear();
  const Eigen::Vector3d at_mean = D * points.mean + (T_a.translation() - T_b.translation());
  return std::sqrt(std::max(0.0, at_mean.squaredNorm() + (D.transpose() * D * points.covariance).trace()));
}

}  // namespace gasp
