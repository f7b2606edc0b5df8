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

}  // namespace gasp
