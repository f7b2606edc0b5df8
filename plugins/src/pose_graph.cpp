#include "gasp/mrpt/pose_graph.h"

#include <mrpt/poses/CPose3DPDFGaussianInf.h>

#include <Eigen/Cholesky>

#include <algorithm>
#include <cmath>
#include <string>

#include "gasp/core/error.h"
#include "gasp/mrpt/pose_covariance.h"
#include "gasp/rawlog/observation_conversion.h"

namespace gasp {

PoseGraphExport toPoseGraph(const std::vector<OdometryFrame>& frames, const std::vector<PoseConstraint>& constraints,
                            const Isometry3& T_robot_camera) {
  std::vector<Isometry3> T_world_camera;
  T_world_camera.reserve(frames.size());
  for (const OdometryFrame& f : frames) T_world_camera.push_back(f.T_world_camera);
  return toPoseGraph(T_world_camera, constraints, T_robot_camera);
}

PoseGraphExport toPoseGraph(const std::vector<Isometry3>& T_world_camera, const std::vector<PoseConstraint>& constraints,
                            const Isometry3& T_robot_camera) {
  PoseGraphExport out;
  const Isometry3 T_camera_robot = T_robot_camera.inverse();
  for (std::size_t i = 0; i < T_world_camera.size(); ++i) out.graph.nodes[i] = toCPose3D(T_world_camera[i] * T_camera_robot);
  out.graph.root = 0;
  for (const PoseConstraint& c : constraints) {
    if (c.from >= T_world_camera.size() || c.to >= T_world_camera.size())
      throw Error("toPoseGraph: a constraint names frame " + std::to_string(std::max(c.from, c.to)) + " of " +
                  std::to_string(T_world_camera.size()));
    const auto edge = edgeFromConstraint(c, T_robot_camera, T_robot_camera);
    if (!edge) {
      ++out.skipped_constraints;
      continue;
    }
    out.graph.insertEdge(c.from, c.to, *edge);
  }
  return out;
}

std::optional<mrpt::poses::CPose3DPDFGaussianInf> edgeFromConstraint(const PoseConstraint& c,
                                                                     const Isometry3& T_robot_camera_from,
                                                                     const Isometry3& T_robot_camera_to) {
  // T_rfrom_rto = S_from T_cfrom_cto S_to^-1; the left perturbation moves with S_from only.
  const Isometry3 T = T_robot_camera_from * c.T_from_to * T_robot_camera_to.inverse();
  const auto pdf = poseWithInformation(T, informationInFrame(c.information, T_robot_camera_from));
  if (!pdf) return std::nullopt;
  mrpt::poses::CPose3DPDFGaussianInf edge;
  edge.copyFrom(*pdf);
  for (int r = 0; r < 6; ++r)
    for (int k = 0; k < 6; ++k)
      if (!std::isfinite(edge.cov_inv(r, k))) return std::nullopt;  // e.g. at pitch +-90 deg
  return edge;
}

std::optional<PoseConstraint> constraintFromEdge(std::size_t from, std::size_t to,
                                                 const mrpt::poses::CPose3DPDFGaussianInf& edge,
                                                 const Isometry3& T_robot_camera_from,
                                                 const Isometry3& T_robot_camera_to) {
  const Isometry3 T_r = fromCPose3D(edge.mean);
  Matrix6 I_ypr;
  for (int r = 0; r < 6; ++r)
    for (int k = 0; k < 6; ++k) I_ypr(r, k) = edge.cov_inv(r, k);
  if (!I_ypr.allFinite() || !T_r.matrix().allFinite()) return std::nullopt;
  // cov_ypr = J cov_xi J^T, so I_xi = J^T I_ypr J (J invertible away from pitch = +-90 deg).
  const Matrix6 J = yprJacobian(T_r);
  Matrix6 I_robot = J.transpose() * I_ypr * J;
  I_robot = 0.5 * (I_robot + I_robot.transpose());
  // Robot frame `from` -> camera frame `from`: I_c = Ad(S)^T I_r Ad(S), the inverse of informationInFrame().
  const Matrix6 Ad = adjoint(T_robot_camera_from);
  Matrix6 I_camera = Ad.transpose() * I_robot * Ad;
  I_camera = 0.5 * (I_camera + I_camera.transpose());
  const Eigen::LDLT<Matrix6> ldlt(I_camera);
  if (!I_camera.allFinite() || ldlt.info() != Eigen::Success || !ldlt.isPositive() ||
      (ldlt.vectorD().array() <= 0).any())
    return std::nullopt;
  PoseConstraint c;
  c.from = from;
  c.to = to;
  c.T_from_to = T_robot_camera_from.inverse() * T_r * T_robot_camera_to;
  c.information = I_camera;
  return c;
}

}  // namespace gasp
