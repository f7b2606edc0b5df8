#include "gasp/slam/pose_graph_marginals.h"

#include <ceres/ceres.h>

#include <chrono>
#include <utility>

#include "gasp/core/error.h"
#include "gasp/core/pose_perturbation.h"
#include "gasp/slam/pose_graph.h"
#include "pose_graph_problem.h"

namespace gasp {

namespace {

/// d omega / d q for a perturbed unit quaternion q' = q + dq (Eigen's x y z w order), with omega
/// the rotation vector of q' q^-1 (a left perturbation): omega = 2 vec(dq q^-1) to first order,
/// = 2 [w I + [v]x, -v] dq for q = (v, w).
Eigen::Matrix<double, 3, 4> leftRotationOfQuaternion(const Eigen::Quaterniond& q) {
  Eigen::Matrix<double, 3, 4> M;
  M.leftCols<3>() = 2.0 * (q.w() * Eigen::Matrix3d::Identity() + skew(q.vec()));
  M.col(3) = -2.0 * q.vec();
  return M;
}

}  // namespace

Eigen::Matrix3d positionCovariance(const Matrix6d& covariance, const Isometry3& T_world_node) {
  Eigen::Matrix<double, 3, 6> B;
  B.leftCols<3>() = Eigen::Matrix3d::Identity();
  B.rightCols<3>() = -skew(T_world_node.translation());
  const Eigen::Matrix3d C = B * covariance * B.transpose();
  return 0.5 * (C + C.transpose());
}

PoseGraphMarginals poseGraphMarginals(const std::vector<Isometry3>& T_world_node,
                                      const std::vector<PoseConstraint>& edges, int num_threads) {
  const auto start = std::chrono::steady_clock::now();
  const std::size_t n = T_world_node.size();
  if (num_threads < 1) throw Error("pose graph marginals: num_threads must be positive");
  detail::PoseGraphProblem graph(T_world_node, edges);  // the optimiser's problem

  PoseGraphMarginals out;
  out.covariance.assign(n, std::nullopt);
  out.piece_root = graph.roots();
  std::vector<std::size_t> free_nodes;
  for (std::size_t i = 0; i < n; ++i)
    if (graph.used(i) && !graph.fixed(i)) free_nodes.push_back(i);

  std::vector<std::pair<const double*, const double*>> blocks;
  blocks.reserve(3 * free_nodes.size());
  for (const std::size_t i : free_nodes) {
    blocks.emplace_back(graph.q(i), graph.q(i));
    blocks.emplace_back(graph.q(i), graph.t(i));
    blocks.emplace_back(graph.t(i), graph.t(i));
  }
  ceres::Covariance::Options options;
  options.algorithm_type = ceres::SPARSE_QR;
  options.num_threads = num_threads;
  ceres::Covariance covariance(options);
  if (!blocks.empty() && !covariance.Compute(blocks, &graph.problem())) {
    out.message = "Ceres could not compute the covariance (a rank-deficient Jacobian: some direction is unobservable)";
    out.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return out;
  }
  for (std::size_t i = 0; i < n; ++i)
    if (graph.fixed(i)) out.covariance[i] = Matrix6d::Zero();
  for (const std::size_t i : free_nodes) {
    // Ambient blocks (quaternion x y z w, translation), row-major as Ceres writes them.
    Eigen::Matrix<double, 4, 4, Eigen::RowMajor> C_qq;
    Eigen::Matrix<double, 4, 3, Eigen::RowMajor> C_qt;
    Eigen::Matrix<double, 3, 3, Eigen::RowMajor> C_tt;
    covariance.GetCovarianceBlock(graph.q(i), graph.q(i), C_qq.data());
    covariance.GetCovarianceBlock(graph.q(i), graph.t(i), C_qt.data());
    covariance.GetCovarianceBlock(graph.t(i), graph.t(i), C_tt.data());
    // z = [dt; omega] with omega = M dq; then xi = [dt + [t]x omega; omega] (Exp(xi) T moves
    // the translation by omega x t + rho, so rho = dt - omega x t).
    const Eigen::Matrix<double, 3, 4> M = leftRotationOfQuaternion(graph.quaternion(i));
    Matrix6d C_z;
    C_z.topLeftCorner<3, 3>() = C_tt;
    C_z.topRightCorner<3, 3>() = (M * C_qt).transpose();
    C_z.bottomLeftCorner<3, 3>() = M * C_qt;
    C_z.bottomRightCorner<3, 3>() = M * C_qq * M.transpose();
    Matrix6d A = Matrix6d::Identity();
    A.topRightCorner<3, 3>() = skew(graph.translation(i));
    const Matrix6d C = A * C_z * A.transpose();
    out.covariance[i] = 0.5 * (C + C.transpose());
  }
  out.computed = true;
  out.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace gasp
