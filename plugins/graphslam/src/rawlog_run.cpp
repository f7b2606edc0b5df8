#include "gasp/graphslam/rawlog_run.h"

#include <cstdio>
#include <utility>

#include "gasp/core/error.h"
#include "gasp/mrpt/keyframe_map.h"
#include "gasp/rawlog/observation_conversion.h"

namespace gasp::graphslam {

namespace {

/// A scan that cannot be converted keeps what it has: its timestamp, the identity mounting
/// (mounted = false) and no depth.
NodeRecord recordOf(const mrpt::obs::CObservation3DRangeScan::Ptr& scan, bool keep_depth) {
  NodeRecord record;
  if (!scan) return record;
  record.timestamp = mrpt::Clock::toDouble(scan->timestamp);
  try {
    RgbdFrame frame = frameFromObservation(*scan, "scan", ColourImage::Skip);
    record.T_robot_camera = frame.T_robot_camera;
    record.mounted = true;
    if (keep_depth) record.frame = std::move(frame);  // a map keeps depth only (the raw values as stored)
  } catch (const Error&) {
  }
  return record;
}

/// The depth of the keyframe GASP's node decider added in this step: the scan's, or the view it
/// was registered with when it was deskewed (keyframe_map.h).
std::optional<RgbdFrame> keyframeDepth(const mrpt::obs::CObservation3DRangeScan::Ptr& scan,
                                       const CGaspOdometryNRD& node_decider, std::size_t keyframe) {
  std::optional<RgbdFrame> frame = recordOf(scan, true).frame;
  const DepthOdometry* odometry = node_decider.odometry();
  const std::size_t index = node_decider.nodeFrames()[keyframe];
  if (frame && odometry && index < odometry->frames().size() && odometry->frames()[index].deskewed) {
    if (index + 1 == odometry->frames().size() && odometry->keyframeView())
      frame = withViewDepth(std::move(*frame), *odometry->keyframeView());
    else  // not expected: the node decider adds a keyframe in the step of its scan
      std::fprintf(stderr, "warning: keyframe %zu was deskewed but its view is gone; the map keeps its recorded depth\n",
                   index);
  }
  return frame;
}

}  // namespace

RawlogRunResult runOverRawlog(GraphSlamEngine& engine, RawlogEntries& entries, const std::string& sensor_label,
                              const CGaspOdometryNRD* node_decider, const RawlogRunOptions& options) {
  RawlogRunResult run;
  SkippedMotion skipped_motion;  // odometry of the steps left out
  mrpt::obs::CObservation3DRangeScan::Ptr first_scan;
  // GASP's node decider: the depth of each keyframe, in node order (the root's is known a step
  // before the root enters the graph, with the second node).
  std::vector<std::optional<RgbdFrame>> keyframe_depth;
  while (!options.selection.done(run.scans)) {
    std::optional<RawlogEntry> next_entry;
    try {
      next_entry = entries.next();
    } catch (const Error& e) {
      if (run.steps == 0) throw;
      run.complete = false;  // the entries before the damage are kept
      run.input_error = e.what();
      break;
    }
    if (!next_entry) break;
    auto [action, observations, observation] = *next_entry;
    std::size_t entry = entries.objectsRead();  // the engine takes it by reference
    const auto scan = depthScanOf(observations, observation, sensor_label);
    const bool left_out = scan ? !options.selection.uses(run.seen_scans++) : observations && !skipped_motion.empty();
    if (left_out) {
      if (observations) skipped_motion.add(action);
      continue;
    }
    if (observations) action = skipped_motion.prepend(action);
    if (observations && (!action || action->size() == 0)) action = noMotionAction();
    if (scan) ++run.scans;
    if (scan && !first_scan) first_scan = scan;
    engine._execGraphSlamStep(action, observations, observation, entry);
    ++run.steps;
    const std::size_t n = engine.getGraph().nodeCount();
    while (run.nodes.size() < n) {
      if (node_decider) {  // told exactly after the run
        run.nodes.emplace_back();
        continue;
      }
      const auto& node_scan = run.nodes.empty() ? first_scan : scan;
      NodeRecord record = recordOf(node_scan, options.keep_depth);
      if (!node_scan) {
        const auto t = stepTimestamp(action, observations, observation);
        if (t != INVALID_TIMESTAMP) record.timestamp = mrpt::Clock::toDouble(t);
      }
      if (!record.mounted && !run.nodes.empty()) record.T_robot_camera = run.nodes.back().T_robot_camera;
      run.nodes.push_back(std::move(record));
    }
    while (node_decider && options.keep_depth && keyframe_depth.size() < node_decider->nodeFrames().size())
      keyframe_depth.push_back(keyframeDepth(scan, *node_decider, keyframe_depth.size()));
    if (options.progress_every > 0 && run.steps % options.progress_every == 0)
      std::fprintf(stderr, "entry %zu: %zu nodes, %zu edges\n", entries.objectsRead(), n,
                   engine.getGraph().edgeCount());
  }
  if (node_decider && node_decider->odometry()) {  // the keyframes' exact times and mountings
    for (std::size_t i = 0; i < run.nodes.size() && i < node_decider->nodeFrames().size(); ++i) {
      run.nodes[i].timestamp = node_decider->odometry()->frames()[node_decider->nodeFrames()[i]].timestamp;
      run.nodes[i].T_robot_camera = node_decider->nodeRobotCamera()[i];
      run.nodes[i].mounted = true;
      if (i < keyframe_depth.size()) run.nodes[i].frame = std::move(keyframe_depth[i]);
    }
  }
  return run;
}

void finishGraph(CGaspPoseGraphGSO* optimiser, CGaspLoopClosureERD* loop_closer) {
  for (;;) {
    if (optimiser) optimiser->optimizeNow();
    if (!loop_closer || loop_closer->syncWithGraph() == 0 || !optimiser) return;
  }
}

Trajectory nodeTrajectory(const Graph3D& graph, const std::vector<NodeRecord>& nodes) {
  if (nodes.size() != graph.nodeCount())
    throw Error("nodeTrajectory: " + std::to_string(nodes.size()) + " node records for a graph of " +
                std::to_string(graph.nodeCount()) + " nodes");
  Trajectory trajectory;
  for (std::size_t i = 0; i < nodes.size(); ++i)
    trajectory.push_back({nodes[i].timestamp, fromCPose3D(graph.nodes.at(i)) * nodes[i].T_robot_camera});
  return trajectory;
}

}  // namespace gasp::graphslam
