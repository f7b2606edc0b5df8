#pragma once
// Internal: the point-to-plane residuals of pose_problem.cpp on T_target_source = (q, t), q an
// Eigen quaternion (x, y, z, w) on ceres::EigenQuaternionManifold. Each exists twice: as a
// templated functor (the definition, used by the tests with ceres::AutoDiffCostFunction) and as
// a cost function with the same value and analytic derivatives (what the refinement uses:
// thousands of dense terms per round, about a third of the Jacobian time of automatic
// differentiation).
//
// Eigen rotates v by q as v + 2 w (u x v) + 2 u x (u x v), u = (x, y, z), also for q off the
// unit sphere, so the derivatives below are those of that expression:
//   d/dw = 2 (u x v)
//   d/du = -2 w [v]x + 2 ((u . v) I + u v^T - 2 v u^T)
#include <ceres/ceres.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace gasp::detail {

template <typename T>
using PlaneVec3 = Eigen::Matrix<T, 3, 1>;

/// r = n . (R p + t - q): a source point against a target plane (forward and dense terms).
struct TargetPlaneResidual {
  Eigen::Vector3d p, q, n;
  template <typename T>
  bool operator()(const T* quaternion, const T* translation, T* r) const {
    const Eigen::Map<const Eigen::Quaternion<T>> R(quaternion);
    const Eigen::Map<const PlaneVec3<T>> t(translation);
    r[0] = n.cast<T>().dot(R * p.cast<T>() + t - q.cast<T>());
    return true;
  }
};

/// r = n_s . (R^T (p_t - t) - p_s): a target point, mapped back, against a source plane.
struct SourcePlaneResidual {
  Eigen::Vector3d p_s, n_s, p_t;
  template <typename T>
  bool operator()(const T* quaternion, const T* translation, T* r) const {
    const Eigen::Map<const Eigen::Quaternion<T>> R(quaternion);
    const Eigen::Map<const PlaneVec3<T>> t(translation);
    r[0] = n_s.cast<T>().dot(R.conjugate() * (p_t.cast<T>() - t) - p_s.cast<T>());
    return true;
  }
};

namespace plane_residuals {

inline Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

/// v rotated by the quaternion (u, w), as Eigen computes it.
inline Eigen::Vector3d rotate(const Eigen::Vector3d& u, double w, const Eigen::Vector3d& v) {
  const Eigen::Vector3d uv = 2.0 * u.cross(v);
  return v + w * uv + u.cross(uv);
}

/// d(rotate(u, w, v)) / d(u, w) as a 3 x 4 matrix (columns x, y, z, w), rotate = Eigen's formula.
inline Eigen::Matrix<double, 3, 4> rotationJacobian(const Eigen::Vector3d& u, double w, const Eigen::Vector3d& v) {
  Eigen::Matrix<double, 3, 4> J;
  J.leftCols<3>() = -2.0 * w * skew(v) +
                    2.0 * (u.dot(v) * Eigen::Matrix3d::Identity() + u * v.transpose() - 2.0 * v * u.transpose());
  J.col(3) = 2.0 * u.cross(v);
  return J;
}

}  // namespace plane_residuals

/// TargetPlaneResidual with analytic derivatives.
class TargetPlaneCost final : public ceres::SizedCostFunction<1, 4, 3> {
 public:
  explicit TargetPlaneCost(const TargetPlaneResidual& r) : r_(r) {}
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const double* q = parameters[0];
    const Eigen::Vector3d u(q[0], q[1], q[2]);
    const double w = q[3];
    const Eigen::Vector3d t(parameters[1][0], parameters[1][1], parameters[1][2]);
    residuals[0] = r_.n.dot(plane_residuals::rotate(u, w, r_.p) + t - r_.q);
    if (jacobians) {
      if (jacobians[0]) {
        Eigen::Map<Eigen::Matrix<double, 1, 4>> Jq(jacobians[0]);
        Jq = r_.n.transpose() * plane_residuals::rotationJacobian(u, w, r_.p);
      }
      if (jacobians[1]) {
        Eigen::Map<Eigen::Matrix<double, 1, 3>> Jt(jacobians[1]);
        Jt = r_.n.transpose();
      }
    }
    return true;
  }

 private:
  TargetPlaneResidual r_;
};

/// SourcePlaneResidual with analytic derivatives (R^T v rotates by the conjugate (-u, w)).
class SourcePlaneCost final : public ceres::SizedCostFunction<1, 4, 3> {
 public:
  explicit SourcePlaneCost(const SourcePlaneResidual& r) : r_(r) {}
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const double* q = parameters[0];
    const Eigen::Vector3d u(-q[0], -q[1], -q[2]);  // the conjugate's vector part
    const double w = q[3];
    const Eigen::Vector3d t(parameters[1][0], parameters[1][1], parameters[1][2]);
    const Eigen::Vector3d v = r_.p_t - t;
    residuals[0] = r_.n_s.dot(plane_residuals::rotate(u, w, v) - r_.p_s);
    if (jacobians) {
      if (jacobians[0]) {
        Eigen::Matrix<double, 3, 4> J = plane_residuals::rotationJacobian(u, w, v);
        J.leftCols<3>() = -J.leftCols<3>();  // d(-x)/dx
        Eigen::Map<Eigen::Matrix<double, 1, 4>> Jq(jacobians[0]);
        Jq = r_.n_s.transpose() * J;
      }
      if (jacobians[1]) {
        // d(Rv)/dv = I + 2 w [u]x + 2 [u]x [u]x (the rotation by the conjugate); dv/dt = -I.
        const Eigen::Matrix3d S = plane_residuals::skew(u);
        const Eigen::Matrix3d M = Eigen::Matrix3d::Identity() + 2.0 * w * S + 2.0 * S * S;
        Eigen::Map<Eigen::Matrix<double, 1, 3>> Jt(jacobians[1]);
        Jt = -r_.n_s.transpose() * M;
      }
    }
    return true;
  }

 private:
  SourcePlaneResidual r_;
};

}  // namespace gasp::detail
