#include "gasp/graphslam/CGaspOdometryNRD.h"

#include <mrpt/config/CConfigFile.h>
#include <mrpt/system/filesystem.h>

#include <Eigen/Cholesky>

#include <iostream>
#include <set>
#include <sstream>
#include <utility>

#include "gasp/core/error.h"
#include "gasp/params/params_io.h"
#include "gasp/mrpt/pose_graph.h"
#include "gasp/rawlog/observation_conversion.h"
#include "gasp/slam/pose_graph.h"

namespace gasp::graphslam {

namespace {
const char* const kSection = "CGaspOdometryNRD";
}

CGaspOdometryNRD::CGaspOdometryNRD() {
  this->initializeLoggers(kSection);
  this->setMinLoggingLevel(mrpt::system::LVL_WARN);  // until loadParams() reads class_verbosity
}

void CGaspOdometryNRD::setParams(const OdometryParams& params) {
  if (odometry_) throw Error("CGaspOdometryNRD: parameters can only be set before the first scan");
  validate(params);
  params_ = params;
}

Isometry3 CGaspOdometryNRD::robotPose(std::size_t frame) const {
  return odometry_->frames()[frame].T_world_camera * frame_robot_camera_[frame].inverse();
}

mrpt::poses::CPose3DPDFGaussianInf CGaspOdometryNRD::edgeTo(std::size_t frame) {
  const std::size_t from = node_frames_.back();
  const auto path = composeAlongTree(odometry_->constraints(), odometry_->frames().size(), from, frame);
  if (path) {
    const Eigen::LDLT<Matrix6d> ldlt(path->covariance);
    if (ldlt.info() == Eigen::Success && ldlt.isPositive()) {
      PoseConstraint c;
      c.from = from;
      c.to = frame;
      c.T_from_to = path->T_a_b;
      c.information = ldlt.solve(Matrix6d::Identity());
      if (auto edge = edgeFromConstraint(c, frame_robot_camera_[from], frame_robot_camera_[frame])) return *edge;
    }
  }
  // The odometry lost track in between: its prediction, with no weight.
  ++break_edges_;
  MRPT_LOG_WARN_STREAM("tracking was lost between frames " << from << " and " << frame
                                                           << ": the edge between their nodes is a break");
  mrpt::poses::CPose3DPDFGaussianInf edge;
  edge.mean = toCPose3D(robotPose(from).inverse() * robotPose(frame));
  edge.cov_inv.setIdentity();
  edge.cov_inv *= kBreakInformation;
  return edge;
}

bool CGaspOdometryNRD::updateState(mrpt::obs::CActionCollection::Ptr /*action*/,
                                   mrpt::obs::CSensoryFrame::Ptr observations, mrpt::obs::CObservation::Ptr observation) {
  const auto scan = depthScanOf(observations, observation, sensor_label_);
  if (!scan) return false;
  std::size_t index = 0;
  try {
    const RgbdFrame frame = frameFromObservation(*scan, "scan '" + scan->sensorLabel + "'", ColourImage::Skip);
    if (!odometry_) odometry_.emplace(params_, frame.T_robot_camera);  // world = the first robot frame
    const OdometryFrame& f = odometry_->addFrame(frame.timestamp, frame.depth_m, frame.depth_intrinsics);
    frame_robot_camera_.push_back(frame.T_robot_camera);
    index = f.index;
    if (!f.keyframe) return false;
  } catch (const Error& e) {
    ++skipped_scans_;
    MRPT_LOG_WARN_STREAM("scan skipped: " << e.what());
    return false;
  }
  if (node_frames_.empty()) {
    // The first keyframe: the root, registered with the next node (CGraphSlamEngine expects the
    // first registration to add two nodes).
    node_frames_.push_back(index);
    node_robot_camera_.push_back(frame_robot_camera_[index]);
    return false;
  }
  const mrpt::poses::CPose3DPDFGaussianInf edge = edgeTo(index);
  if (m_graph->nodes.empty()) {
    m_graph->root = 0;
    m_graph->nodes[0] = toCPose3D(robotPose(node_frames_[0]));
    m_prev_registered_nodeID = 0;
  }
  const mrpt::graphs::TNodeID from = m_prev_registered_nodeID, to = m_graph->nodeCount();
  m_graph->nodes[to] = m_graph->nodes.at(from) + edge.mean;
  m_graph->insertEdgeAtEnd(from, to, edge);
  m_prev_registered_nodeID = to;
  node_frames_.push_back(index);
  node_robot_camera_.push_back(frame_robot_camera_[index]);
  return true;
}

CGaspOdometryNRD::global_pose_t CGaspOdometryNRD::getCurrentRobotPosEstimation() const {
  if (!odometry_ || odometry_->frames().empty()) return {};
  const std::size_t latest = odometry_->frames().size() - 1;
  if (m_prev_registered_nodeID == mrpt::graphs::INVALID_NODEID || !m_graph) return toCPose3D(robotPose(latest));
  const Isometry3 T_node_latest = robotPose(node_frames_.back()).inverse() * robotPose(latest);
  return m_graph->nodes.at(m_prev_registered_nodeID) + toCPose3D(T_node_latest);
}

void CGaspOdometryNRD::loadParams(const std::string& source_fname) {
  if (!mrpt::system::fileExists(source_fname))
    THROW_EXCEPTION_FMT("CGaspOdometryNRD: configuration file not found: %s", source_fname.c_str());
  const mrpt::config::CConfigFile cfg(source_fname);
  OdometryParams p = params_;
  readOdometryParams(cfg, kSection, p, {"sensor_label", "class_verbosity"});
  int verbosity = static_cast<int>(getMinLoggingLevel());
  readValue(cfg, kSection, "class_verbosity", verbosity);
  try {
    setParams(p);
  } catch (const Error& e) {
    THROW_EXCEPTION_FMT("[%s]: %s", kSection, e.what());
  }
  sensor_label_ = cfg.read_string(kSection, "sensor_label", sensor_label_);
  setMinLoggingLevel(static_cast<mrpt::system::VerbosityLevel>(verbosity));
}

void CGaspOdometryNRD::printParams() const {
  std::cout << "------------[ CGaspOdometryNRD ]------------\n"
            << "keyframe_distance_m       = " << params_.keyframe_distance_m << '\n'
            << "keyframe_angle_deg        = " << params_.keyframe_angle_deg << '\n'
            << "max_speed_mps             = " << params_.max_speed_mps << '\n'
            << "max_rate_radps            = " << params_.max_rate_radps << '\n'
            << "rolling_shutter_readout_s = " << params_.rolling_shutter_readout_s << '\n'
            << "scene_change              = " << (params_.scene_change.enabled ? 1 : 0) << " (violations "
            << params_.scene_change.max_violation_ratio << ", " << params_.scene_change.max_two_way_violation_ratio
            << " from both, occluded " << params_.scene_change.max_occluded_ratio << "; gate "
            << params_.scene_change.gate_m << " m + " << params_.scene_change.max_accel_mps2 << " m/s^2, "
            << params_.scene_change.gate_deg << " deg + " << params_.scene_change.max_angular_accel_radps2
            << " rad/s^2, at most " << params_.scene_change.max_gate_m << " m / "
            << params_.scene_change.max_gate_deg << " deg)\n"
            << "sensor_label              = " << (sensor_label_.empty() ? "(any)" : sensor_label_) << '\n';
}

void CGaspOdometryNRD::getDescriptiveReport(std::string* report_str) const {
  CNodeRegistrationDecider<Graph3D>::getDescriptiveReport(report_str);
  std::ostringstream ss;
  ss << "GASP depth odometry: a node per keyframe\n";
  if (odometry_)
    ss << "scans: " << odometry_->frames().size() << ", tracked: " << odometry_->trackedCount()
       << " (through a scene change: " << odometry_->sceneChangeCount() << ")"
       << ", keyframes: " << odometry_->keyframeCount() << '\n';
  ss << "nodes: " << node_frames_.size() << ", break edges: " << break_edges_ << ", scans skipped: " << skipped_scans_
     << '\n';
  *report_str += ss.str();
}

}  // namespace gasp::graphslam
