#pragma once
/// \file CGaspOdometryNRD.h mrpt::graphslam node registration decider (NRD) over GASP's depth
/// odometry (gasp/odometry/odometry.h): one node per odometry keyframe.
///
/// Each 3D range scan of the rawlog (format #1 or #2) goes to gasp::DepthOdometry. When the
/// odometry makes a keyframe, a node is registered at the end of the graph with an edge from the
/// previous node: the odometry's relative pose between the two keyframes, composed along its
/// constraints, with its information (GASP's edge information carried along the path, first
/// order, in MRPT's [x y z yaw pitch roll]). Where the odometry lost track between the two, the
/// edge is a break (graph_types.h): the odometry's prediction with no weight. Nodes are robot
/// poses; the world is the first keyframe's robot frame.
///
/// Parameters: ini section [CGaspOdometryNRD] (docs/graphslam.md): the pair keys of params_io.h,
/// keyframe_distance_m, keyframe_angle_deg, max_speed_mps, max_rate_radps,
/// rolling_shutter_readout_s, the scene-change attempt (scene_change.h: scene_change 0/1,
/// scene_change_max_violation_ratio, scene_change_max_two_way_violation_ratio,
/// scene_change_max_occluded_ratio, scene_change_gate_m, scene_change_gate_deg,
/// scene_change_max_accel_mps2, scene_change_max_angular_accel_radps2, scene_change_max_gate_m,
/// scene_change_max_gate_deg), sensor_label,
/// class_verbosity.
#include <mrpt/graphslam/interfaces/CNodeRegistrationDecider.h>

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "gasp/core/pose.h"
#include "gasp/graphslam/graph_types.h"
#include "gasp/odometry/odometry.h"

namespace gasp::graphslam {

class CGaspOdometryNRD : public mrpt::graphslam::deciders::CNodeRegistrationDecider<Graph3D> {
 public:
  CGaspOdometryNRD();

  /// Feeds the step's depth scan to the odometry; true when a node was registered. A scan the
  /// odometry refuses (wrong size, a timestamp not after the previous one, an unconvertible
  /// range image) is skipped with a warning and counted (skippedScans()).
  bool updateState(mrpt::obs::CActionCollection::Ptr action, mrpt::obs::CSensoryFrame::Ptr observations,
                   mrpt::obs::CObservation::Ptr observation) override;
  /// Reads section [CGaspOdometryNRD]; missing keys keep their values, unknown keys and invalid
  /// values throw (std::exception naming the key).
  void loadParams(const std::string& source_fname) override;
  void printParams() const override;
  void getDescriptiveReport(std::string* report_str) const override;
  /// The last node's pose moved by the odometry since its keyframe.
  global_pose_t getCurrentRobotPosEstimation() const override;

  /// Replaces the odometry's parameters (before the first scan; throws gasp::Error if invalid or late).
  void setParams(const OdometryParams& params);
  const OdometryParams& params() const { return params_; }
  void setSensorLabel(const std::string& label) { sensor_label_ = label; }
  /// The 3D range scans used: those with this sensorLabel (empty: the first of any step).
  const std::string& sensorLabel() const { return sensor_label_; }
  /// nullptr before the first scan.
  const DepthOdometry* odometry() const { return odometry_ ? &*odometry_ : nullptr; }
  /// For each node, the odometry's frame index (= the scan's position among the scans used).
  const std::vector<std::size_t>& nodeFrames() const { return node_frames_; }
  /// For each node, the camera's pose on the robot (the scan's sensorPose, optical frame).
  const std::vector<Isometry3>& nodeRobotCamera() const { return node_robot_camera_; }
  std::size_t breakEdges() const { return break_edges_; }
  std::size_t skippedScans() const { return skipped_scans_; }

 private:
  /// T_world_robot of odometry frame i.
  Isometry3 robotPose(std::size_t frame) const;
  /// The edge between the last node's frame and `frame`.
  mrpt::poses::CPose3DPDFGaussianInf edgeTo(std::size_t frame);

  OdometryParams params_;
  std::string sensor_label_;
  std::optional<DepthOdometry> odometry_;
  std::vector<Isometry3> frame_robot_camera_;  ///< per odometry frame
  std::vector<std::size_t> node_frames_;
  std::vector<Isometry3> node_robot_camera_;
  std::size_t break_edges_ = 0;
  std::size_t skipped_scans_ = 0;
};

}  // namespace gasp::graphslam
