#include "gasp/mrpt/pose_graph.h"

#include <mrpt/poses/CPose3DPDFGaussianInf.h>

#include <algorithm>
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
    // T_rfrom_rto = T_robot_camera T_cfrom_cto T_camera_robot; its information moved to robot frame `from`.
    const Isometry3 T = T_robot_camera * c.T_from_to * T_camera_robot;
    const auto pdf = poseWithInformation(T, informationInFrame(c.information, T_robot_camera));
    if (!pdf) {
      ++out.skipped_constraints;
      continue;
    }
    mrpt::poses::CPose3DPDFGaussianInf edge;
    edge.copyFrom(*pdf);
    out.graph.insertEdge(c.from, c.to, edge);
  }
  return out;
}

}  // namespace gasp
