#pragma once
// Private to gasp::slam: the pose-graph edge's residual, shared by the optimiser
// (pose_graph_optimizer.cpp) and the marginals (pose_graph_marginals.cpp), so both see one cost.
#include <ceres/rotation.h>
#include <Eigen/Cholesky>
#include <Eigen/Geometry>

#include <string>
#include <vector>

#include "gasp/core/error.h"
#include "gasp/core/pose.h"
#include "gasp/odometry/pose_constraint.h"

namespace gasp::detail {

/// r = L^T xi with Lambda = L L^T and T_from^-1 T_to = Exp(xi) T_meas (pose_graph.h): translation
/// of E = T_from^-1 T_to T_meas^-1, then the angle-axis of its rotation. Parameter blocks: the
/// unit quaternion (Eigen's x y z w) and the translation of T_world_from, then of T_world_to.
struct EdgeResidual {
  EdgeResidual(const Isometry3& T_meas, const Matrix6d& L_transposed)
      : q_meas_inv(Eigen::Quaterniond(T_meas.rotation()).conjugate()),
        t_meas(T_meas.translation()),
        sqrt_information(L_transposed) {}

  template <typename T>
  bool operator()(const T* q_from_p, const T* t_from_p, const T* q_to_p, const T* t_to_p, T* r) const {
    using Q = Eigen::Quaternion<T>;
    using V = Eigen::Matrix<T, 3, 1>;
    const Eigen::Map<const Q> q_from(q_from_p), q_to(q_to_p);
    const Eigen::Map<const V> t_from(t_from_p), t_to(t_to_p);
    const Q q_from_inv = q_from.conjugate();
    const Q q_est = q_from_inv * q_to;             // rotation of T_from^-1 T_to
    const V t_est = q_from_inv * (t_to - t_from);  // its translation
    const Q q_e = q_est * q_meas_inv.cast<T>();    // E's rotation
    const V t_e = t_est - q_e * t_meas.cast<T>();  // E's translation
    Eigen::Matrix<T, 6, 1> xi;
    xi.template head<3>() = t_e;
    const T q_wxyz[4] = {q_e.w(), q_e.x(), q_e.y(), q_e.z()};
    T aa[3];
    ceres::QuaternionToAngleAxis(q_wxyz, aa);
    xi(3) = aa[0], xi(4) = aa[1], xi(5) = aa[2];
    Eigen::Map<Eigen::Matrix<T, 6, 1>> residual(r);
    residual = sqrt_information.cast<T>() * xi;
    return true;
  }

  Eigen::Quaterniond q_meas_inv;
  Eigen::Vector3d t_meas;
  Matrix6d sqrt_information;  ///< L^T
};

/// L^T of the constraint's information; throws gasp::Error when it is not finite and positive definite.
inline Matrix6d sqrtInformation(const PoseConstraint& c) {
  const Eigen::LLT<Matrix6d> llt(c.information);
  if (!c.information.allFinite() || llt.info() != Eigen::Success)
    throw Error("pose graph: the information of constraint " + std::to_string(c.from) + " -> " +
                std::to_string(c.to) + " is not positive definite");
  return llt.matrixU();  // L^T
}

/// Throws gasp::Error for a node that is not finite, an edge naming a node out of range, linking a
/// node to itself or not finite (the informations are checked by sqrtInformation()).
inline void checkPoseGraph(const std::vector<Isometry3>& T_world_node, const std::vector<PoseConstraint>& edges) {
  const std::size_t n = T_world_node.size();
  for (std::size_t i = 0; i < n; ++i)
    if (!T_world_node[i].matrix().allFinite()) throw Error("pose graph: node " + std::to_string(i) + " is not finite");
  for (const PoseConstraint& c : edges) {
    if (c.from >= n || c.to >= n || c.from == c.to)
      throw Error("pose graph: constraint " + std::to_string(c.from) + " -> " + std::to_string(c.to) +
                  " names a node out of range or links a node to itself (" + std::to_string(n) + " nodes)");
    if (!c.T_from_to.matrix().allFinite())
      throw Error("pose graph: constraint " + std::to_string(c.from) + " -> " + std::to_string(c.to) + " is not finite");
  }
}

}  // namespace gasp::detail
