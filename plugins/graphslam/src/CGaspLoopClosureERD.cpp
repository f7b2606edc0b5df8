#include "gasp/graphslam/CGaspLoopClosureERD.h"

#include <mrpt/config/CConfigFile.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/system/filesystem.h>

#include <iostream>
#include <map>
#include <set>
#include <sstream>
#include <string>

#include "gasp/core/error.h"
#include "gasp/params/params_io.h"
#include "gasp/mrpt/pose_graph.h"
#include "gasp/rawlog/observation_conversion.h"
#include "gasp/slam/loop_search.h"
#include "gasp/slam/pose_graph.h"

namespace gasp::graphslam {

namespace {
const char* const kSection = "CGaspLoopClosureERD";
}

CGaspLoopClosureERD::CGaspLoopClosureERD() {
  this->initializeLoggers(kSection);
  this->setMinLoggingLevel(mrpt::system::LVL_WARN);  // until loadParams() reads class_verbosity
}

void CGaspLoopClosureERD::setParams(const PairParams& pair, const LoopClosureParams& loop) {
  validate(pair);
  validate(loop);
  // A closure between consecutive nodes would share its key with the node decider's edge.
  if (loop.min_keyframe_gap < 2) throw Error("CGaspLoopClosureERD: min_keyframe_gap must be at least 2");
  pair_ = pair;
  loop_ = loop;
  votes_ = RelocalisationVotes(loop);
}

std::optional<CGaspLoopClosureERD::Node> CGaspLoopClosureERD::keyframeNode(std::size_t id) const {
  // Only for the same sensor's scans (the node decider's keyframe is its own sensor's scan).
  if (!node_decider_ || node_decider_->sensorLabel() != sensor_label_) return std::nullopt;
  const DepthOdometry* odometry = node_decider_->odometry();
  const auto& node_frames = node_decider_->nodeFrames();
  if (!odometry || !odometry->keyframeView() || odometry->frames().empty() || node_frames.size() != id + 1)
    return std::nullopt;
  const OdometryFrame& newest = odometry->frames().back();
  if (!newest.keyframe || newest.index != node_frames[id]) return std::nullopt;
  // The same segmentation parameters, compared as their ini text.
  mrpt::config::CConfigFileMemory mine, theirs;
  writeSuperpixelParams(pair_.segment, mine, "s");
  writeSuperpixelParams(odometry->params().pair.segment, theirs, "s");
  std::string a, b;
  mine.getContent(a);
  theirs.getContent(b);
  if (a != b) return std::nullopt;
  Node node;
  node.view = *odometry->keyframeView();
  node.T_robot_camera = node_decider_->nodeRobotCamera()[id];
  return node;
}

CGaspLoopClosureERD::Node CGaspLoopClosureERD::nodeOf(const mrpt::obs::CObservation3DRangeScan::Ptr& scan,
                                                       std::string* error) {
  Node node;
  if (!scan) return node;
  ++segmentations_;
  try {
    const RgbdFrame frame = frameFromObservation(*scan, "scan '" + scan->sensorLabel + "'", ColourImage::Skip);
    node.T_robot_camera = frame.T_robot_camera;
    node.view = makeDepthView(frame.depth_m, frame.depth_intrinsics, pair_.segment);
  } catch (const Error& e) {
    if (error) *error = e.what();
  }
  return node;
}

bool CGaspLoopClosureERD::updateState(mrpt::obs::CActionCollection::Ptr /*action*/,
                                      mrpt::obs::CSensoryFrame::Ptr observations,
                                      mrpt::obs::CObservation::Ptr observation) {
  m_just_inserted_lc = false;
  if (m_graph) syncWithGraph();  // an optimiser may have removed closures since the last step
  const auto scan = depthScanOf(observations, observation, sensor_label_);
  // The root: the first scan with surface patches, as the odometry's origin is (segmented once,
  // kept until the root is registered).
  if (scan && !root_ && nodes_.empty()) {
    auto shared = keyframeNode(0);
    Node candidate = shared ? std::move(*shared) : nodeOf(scan, nullptr);
    if (candidate.view && !candidate.view->segmentation.patches.empty()) root_ = std::move(candidate);
  }
  const std::size_t n = m_graph->nodeCount();
  if (n <= nodes_.size()) return true;
  // The root takes its scan; the newest node the scan of this step, if it has one (a node an
  // odometry decider registers on a step without a scan has no view: an earlier scan was taken
  // elsewhere); any other node added in the same step has none. A node without a converted scan
  // keeps the previous node's mounting, for the predictions through it.
  const std::size_t first_new = nodes_.size();
  while (nodes_.size() < n) {
    const std::size_t id = nodes_.size();
    if (id == 0) {
      nodes_.push_back(root_ ? std::move(*root_) : Node{});
      root_.reset();
      continue;
    }
    std::string error;
    Node node;
    if (id + 1 == n) {
      if (auto shared = keyframeNode(id)) node = std::move(*shared);
      else node = nodeOf(scan, &error);
    }
    if (!node.view) node.T_robot_camera = nodes_.back().T_robot_camera;
    if (!error.empty()) MRPT_LOG_WARN_STREAM("node " << id << " has no view: " << error);
    nodes_.push_back(std::move(node));
  }
  // Each new node's place descriptor, when the loop search retrieves (the root's too).
  if (loop_.search != LoopSearch::kRadius)
    for (std::size_t id = first_new; id < nodes_.size(); ++id)
      if (nodes_[id].view) places_.add(id, describeKeyframe(*nodes_[id].view, pair_));
  if (loop_.enabled && nodes_.back().view) closeLoops(n - 1);
  return true;
}

std::vector<PoseConstraint> CGaspLoopClosureERD::treeConstraints() const {
  std::vector<PoseConstraint> tree;
  for (auto it = m_graph->edges.begin(); it != m_graph->edges.end(); ++it) {
    const auto [from, to] = it->first;
    if (to >= nodes_.size() || isClosureEdge(*m_graph, it) || isBreakEdge(it->second)) continue;
    if (auto c = constraintFromEdge(from, to, it->second, nodes_[from].T_robot_camera, nodes_[to].T_robot_camera))
      tree.push_back(*c);
  }
  return tree;
}

std::vector<PoseConstraint> CGaspLoopClosureERD::closureConstraints() const {
  std::vector<PoseConstraint> out;
  for (const Closure& c : closures_) out.push_back(c.constraint);
  return out;
}

std::size_t CGaspLoopClosureERD::syncWithGraph() {
  if (!m_graph) return 0;
  std::vector<bool> gone(closures_.size(), false);
  std::map<std::size_t, std::size_t> group_left;  // group -> its votes still in the graph
  std::set<std::size_t> group_hit;                // groups that lost a vote now
  // (Two closures with the same nodes and the same values would be found as one; every closure
  // ends at the node that was newest when it was made, from distinct candidates, so none are.)
  for (std::size_t j = 0; j < closures_.size(); ++j) {
    const Closure& c = closures_[j];
    gone[j] = findEdge(*m_graph, c.constraint.from, c.constraint.to, c.edge) == m_graph->edges.end();
    if (gone[j]) {
      attempts_[c.attempt].accepted = false;
      attempts_[c.attempt].reason = "removed from the graph by the optimiser";
      if (c.group != 0) group_hit.insert(c.group);
    } else if (c.group != 0) {
      ++group_left[c.group];
    }
  }
  std::size_t removed = 0;
  for (std::size_t j = 0; j < closures_.size(); ++j) {
    const Closure& c = closures_[j];
    if (gone[j] || !group_hit.count(c.group) || group_left[c.group] >= loop_.relocalisation_agreeing) continue;
    m_graph->edges.erase(findEdge(*m_graph, c.constraint.from, c.constraint.to, c.edge));
    gone[j] = true;
    ++removed;
    attempts_[c.attempt].accepted = false;
    attempts_[c.attempt].reason = "removed: a vote it joined two pieces with was removed by the optimiser, too few are left";
    MRPT_LOG_WARN_STREAM("relocalisation " << c.constraint.from << " -> " << c.constraint.to
                                           << " removed with the vote the optimiser removed");
  }
  std::vector<Closure> present;
  for (std::size_t j = 0; j < closures_.size(); ++j)
    if (!gone[j]) present.push_back(std::move(closures_[j]));
  closures_.swap(present);
  return removed;
}

void CGaspLoopClosureERD::insert(const PoseConstraint& c, std::size_t attempt, std::size_t group) {
  const auto edge = edgeFromConstraint(c, nodes_[c.from].T_robot_camera, nodes_[c.to].T_robot_camera);
  if (!edge) {
    attempts_[attempt].accepted = false;
    attempts_[attempt].reason = "its information is not positive definite";
    return;
  }
  m_graph->insertEdge(c.from, c.to, *edge);
  closures_.push_back({c, *edge, attempt, group});
  m_just_inserted_lc = true;
  MRPT_LOG_INFO_STREAM((attempts_[attempt].relocalisation ? "relocalisation " : "loop closure ")
                       << c.from << " -> " << c.to << " (" << c.inliers << " inliers)");
}

void CGaspLoopClosureERD::closeLoops(std::size_t k) {
  LoopSearchGraph g;
  g.node_count = nodes_.size();
  g.T_world_camera.assign(g.node_count, Isometry3::Identity());
  for (std::size_t i = 0; i < g.node_count; ++i) {
    if (nodes_[i].view) g.keyframes.push_back(i);  // the nodes that can be registered (k last)
    g.T_world_camera[i] = fromCPose3D(m_graph->nodes.at(i)) * nodes_[i].T_robot_camera;
  }
  g.tree = treeConstraints();
  g.view = [this](std::size_t i) -> const DepthView& { return *nodes_[i].view; };
  g.links = [this, &g] {
    std::vector<PoseConstraint> all = g.tree;
    const std::vector<PoseConstraint> closures = closureConstraints();
    all.insert(all.end(), closures.begin(), closures.end());
    return all;
  };
  g.insert = [this](const PoseConstraint& c, std::size_t attempt, std::size_t group) { insert(c, attempt, group); };
  g.retrieve = [this](std::size_t key) { return retrieveEarlier(places_, key); };
  // The votes enter MRPT's graph together or not at all: each needs an edge (positive definite
  // information). offer() has let them go: they do not wait again.
  g.before_join = [this](const PoseConstraint&, const RelocalisationVotes::Decision& d, const std::vector<std::size_t>&) {
    for (const RelocalisationVotes::Vote& v : d.votes)
      if (!edgeFromConstraint(v.constraint, nodes_[v.constraint.from].T_robot_camera,
                              nodes_[v.constraint.to].T_robot_camera))
        return std::string("not used: a vote of its group has no positive definite information");
    return std::string();
  };
  searchLoops(k, g, pair_, loop_, attempts_, votes_, vote_groups_);
}

void CGaspLoopClosureERD::getEdgesStats(std::map<std::string, int>* edge_type_to_num) const {
  if (edge_type_to_num) (*edge_type_to_num)["lc"] = static_cast<int>(closures_.size());
}

void CGaspLoopClosureERD::loadParams(const std::string& source_fname) {
  if (!mrpt::system::fileExists(source_fname))
    THROW_EXCEPTION_FMT("CGaspLoopClosureERD: configuration file not found: %s", source_fname.c_str());
  const mrpt::config::CConfigFile cfg(source_fname);
  PairParams pair = pair_;
  LoopClosureParams loop = loop_;
  readLoopClosureParams(cfg, kSection, pair, loop, {"sensor_label", "class_verbosity"});
  int verbosity = static_cast<int>(getMinLoggingLevel());
  readValue(cfg, kSection, "class_verbosity", verbosity);
  try {
    setParams(pair, loop);
  } catch (const Error& e) {
    THROW_EXCEPTION_FMT("[%s]: %s", kSection, e.what());
  }
  sensor_label_ = cfg.read_string(kSection, "sensor_label", sensor_label_);
  setMinLoggingLevel(static_cast<mrpt::system::VerbosityLevel>(verbosity));
}

void CGaspLoopClosureERD::printParams() const {
  std::cout << "------------[ CGaspLoopClosureERD ]------------\n"
            << "enabled                    = " << (loop_.enabled ? 1 : 0) << '\n'
            << "search_radius_m            = " << loop_.search_radius_m << '\n'
            << "max_axis_angle_deg         = " << loop_.max_axis_angle_deg << '\n'
            << "min_keyframe_gap           = " << loop_.min_keyframe_gap << '\n'
            << "max_candidates             = " << loop_.max_candidates << '\n'
            << "loop_min_inliers           = " << loop_.min_inliers << '\n'
            << "gate_chi2                  = " << loop_.gate_chi2 << '\n'
            << "relocalisation_candidates  = " << loop_.relocalisation_candidates << '\n'
            << "relocalisation_min_inliers = " << loop_.relocalisation_min_inliers << '\n'
            << "relocalisation_agreeing    = " << loop_.relocalisation_agreeing << '\n'
            << "sensor_label               = " << (sensor_label_.empty() ? "(any)" : sensor_label_) << '\n';
}

void CGaspLoopClosureERD::getDescriptiveReport(std::string* report_str) const {
  CEdgeRegistrationDecider<Graph3D>::getDescriptiveReport(report_str);
  std::size_t relocalisations = 0;
  for (const auto& a : attempts_) relocalisations += a.accepted && a.relocalisation ? 1 : 0;
  std::ostringstream ss;
  ss << "GASP loop closures: " << attempts_.size() << " registrations tried, " << closures_.size()
     << " edges in the graph (" << relocalisations << " relocalisations)\n";
  for (const auto& a : attempts_)
    ss << "  " << a.from << " -> " << a.to << (a.relocalisation ? " (relocalisation)" : "") << ": "
       << (a.accepted ? "in the graph" : a.reason) << ", " << a.inliers << " inliers\n";
  *report_str += ss.str();
}

}  // namespace gasp::graphslam
