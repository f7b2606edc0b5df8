#include "gasp/mrpt/pose_graph.h"

#include <mrpt/poses/CPose3DPDFGaussianInf.h>

#include "gasp/core/error.h"
#include "gasp/mrpt/pose_covariance.h"

namespace gasp {

namespace {
mrpt::poses::CPose3D toMrpt(const Isometry3& T) {
  mrpt::math::CMatrixDouble44 m;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) m(r, c) = T.matrix()(r, c);
  return mrpt::poses::CPose3D(m);
}
}  // namespace

PoseGraphExport toPoseGraph(const std::vector<OdometryFrame>& frames, const std::vector<PoseConstraint>& constraints,
                            const Isometry3& T_robot_camera) {
  PoseGraphExport out;
  const Isometry3 T_camera_robot = T_robot_camera.inverse();
  for (const OdometryFrame& f : frames) out.graph.nodes[f.index] = toMrpt(f.T_world_camera * T_camera_robot);
  out.graph.root = 0;
  for (const PoseConstraint& c : constraints) {
    if (c.from >= frames.size() || c.to >= frames.size())
      throw Error("toPoseGraph: a constraint names frame " + std::to_string(std::max(c.from, c.to)) + " of " +
                  std::to_string(frames.size()));
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
