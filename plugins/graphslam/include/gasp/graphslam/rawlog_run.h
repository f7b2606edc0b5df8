#pragma once
/// \file rawlog_run.h MRPT's graph-SLAM engine fed a rawlog, step by step, as gasp-graphslam runs
/// it: the scans selected (ScanSelection), the odometry of the steps left out carried on
/// (SkippedMotion), and what is known of each node: when and where its scan was taken, and its
/// depth for a map.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "gasp/core/tum_trajectory.h"
#include "gasp/graphslam/CGaspLoopClosureERD.h"
#include "gasp/graphslam/CGaspOdometryNRD.h"
#include "gasp/graphslam/CGaspPoseGraphGSO.h"
#include "gasp/graphslam/engine.h"
#include "gasp/graphslam/scan_selection.h"
#include "gasp/rawlog/rawlog_entries.h"
#include "gasp/rawlog/rgbd_frame.h"

namespace gasp::graphslam {

/// What a run knows of a graph node.
struct NodeRecord {
  double timestamp = 0.0;                                  ///< s: its scan's (or its step's) time
  Isometry3 T_robot_camera = Isometry3::Identity();        ///< the depth camera on the robot
  bool mounted = false;             ///< T_robot_camera is the node's own scan's (else the node before's)
  std::optional<RgbdFrame> frame;   ///< its depth (no colour), when RawlogRunOptions::keep_depth
};

struct RawlogRunOptions {
  ScanSelection selection;           ///< the deciders' scans given to the engine
  bool keep_depth = false;           ///< keep each node's depth (for a map)
  std::size_t progress_every = 100;  ///< a progress line on standard error every N steps given (0: none)
};

struct RawlogRunResult {
  std::size_t steps = 0;          ///< rawlog entries given to the engine
  std::size_t scans = 0;          ///< the deciders' scans given to it
  std::size_t seen_scans = 0;     ///< the deciders' scans read (given or left out)
  std::vector<NodeRecord> nodes;  ///< one per graph node, in node order
  /// The rawlog ended with an error (truncated or corrupt) after the entries given: the graph
  /// holds those, `input_error` says why the rest is missing.
  bool complete = true;
  std::string input_error;
};

/// Feeds `entries` to `engine` until the rawlog ends or the selection is done. The deciders' scans
/// are those with `sensor_label` (empty: the first of any step). A scan left out is not given to
/// the engine; in format #1 its step's motion goes with the next given step that has a scan
/// (steps without a scan in between are held too, and their other observations are lost). A
/// format-#1 step with no action gets one without motion (the engine reads the first action of
/// every such step).
///
/// Node records: with GASP's node decider (`node_decider`, else nullptr), each node is a keyframe
/// of its odometry, whose time and mounting are exact, and whose depth is the keyframe's as it was
/// registered (deskewed, if it was). With any other node decider, the root takes the first scan
/// given and each newer node the scan of the step that added it; a node added on a step without
/// such a scan gets the step's time, the mounting of the node before it, and no depth.
/// A rawlog that cannot be read on (gasp::Error from `entries`) ends the run with what was given
/// before (RawlogRunResult::complete false); it throws what the engine throws, and the reader's
/// error when not even one entry could be read.
RawlogRunResult runOverRawlog(GraphSlamEngine& engine, RawlogEntries& entries, const std::string& sensor_label,
                              const CGaspOdometryNRD* node_decider, const RawlogRunOptions& options);

/// The final optimisation: `optimiser->optimizeNow()`, then `loop_closer->syncWithGraph()` (the
/// closures the optimiser removed), again while the loop closer takes edges out with them.
/// Either may be nullptr (another class in its place); without the optimiser nothing is
/// optimised. The engine re-derives node poses along a spanning tree at every node it adds, so a
/// graph is saved optimised only after this.
void finishGraph(CGaspPoseGraphGSO* optimiser, CGaspLoopClosureERD* loop_closer);

/// The nodes' depth-camera trajectory (world = the root's robot frame): each node's pose in
/// `graph` times its mounting, at its time. `nodes` holds one record per graph node.
Trajectory nodeTrajectory(const Graph3D& graph, const std::vector<NodeRecord>& nodes);

}  // namespace gasp::graphslam
