#pragma once
/// \file pose_graph.h GASP's odometry (gasp/odometry/odometry.h) or SLAM (gasp/slam) as an MRPT pose graph, ready for
/// mrpt::graphslam's optimisers and for CNetworkOfPoses::saveToTextFile (VERTEX3 / EDGE3 lines).
#include <mrpt/graphs/CNetworkOfPoses.h>
#include <mrpt/poses/CPose3DPDFGaussianInf.h>

#include <cstddef>
#include <optional>
#include <vector>

#include "gasp/core/pose.h"
#include "gasp/odometry/odometry.h"

namespace gasp {

struct PoseGraphExport {
  mrpt::graphs::CNetworkOfPoses3DInf graph;
  /// Constraints left out because their information is not positive definite (no covariance
  /// can be claimed for them; GASP's edge information, with its model error, always is).
  std::size_t skipped_constraints = 0;
};

/// Node i = frame i, at T_world_robot = T_world_camera T_robot_camera^-1; edge from -> to = the
/// pose of robot frame `to` in robot frame `from`, with its information over MRPT's
/// [x y z yaw pitch roll] (pose_covariance.h, first order). T_robot_camera is the camera's pose on
/// the robot (RgbdFrame::T_robot_camera, from MRPT's sensorPose); the identity keeps GASP's optical
/// camera frames (x right, y down, z forward). The root is node 0.
PoseGraphExport toPoseGraph(const std::vector<OdometryFrame>& frames, const std::vector<PoseConstraint>& constraints,
                            const Isometry3& T_robot_camera = Isometry3::Identity());

/// The same with node i at T_world_camera[i] (e.g. DepthSlam::poses(), optimised); loop closures
/// are edges like any other.
PoseGraphExport toPoseGraph(const std::vector<Isometry3>& T_world_camera, const std::vector<PoseConstraint>& constraints,
                            const Isometry3& T_robot_camera = Isometry3::Identity());

/// One GASP constraint between camera frames (PoseConstraint: T_from_to and its information over
/// the left perturbation in camera frame `from`) as an MRPT graph edge between the robot frames:
/// T_rfrom_rto = S_from T_from_to S_to^-1 with S = T_robot_camera of each node, the information
/// carried to robot frame `from` and converted to [x y z yaw pitch roll] (pose_covariance.h,
/// first order). nullopt when the information is not positive definite.
std::optional<mrpt::poses::CPose3DPDFGaussianInf> edgeFromConstraint(const PoseConstraint& c,
                                                                     const Isometry3& T_robot_camera_from,
                                                                     const Isometry3& T_robot_camera_to);
/// The inverse: an MRPT edge between robot frames `from` -> `to` as a GASP constraint between
/// the camera frames, its information over the left perturbation in camera frame `from`
/// (I = J^T I_ypr J, then carried by the camera mounting). nullopt when the edge's information
/// is not finite and positive definite.
std::optional<PoseConstraint> constraintFromEdge(std::size_t from, std::size_t to,
                                                 const mrpt::poses::CPose3DPDFGaussianInf& edge,
                                                 const Isometry3& T_robot_camera_from,
                                                 const Isometry3& T_robot_camera_to);

}  // namespace gasp
