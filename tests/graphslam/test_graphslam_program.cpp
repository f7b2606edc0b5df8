// gasp-graphslam end to end: a simulated rawlog, its outputs (trajectory, graph, MRPT's
// reports), the listings, a real sequence that revisits its places, and the exit codes of bad input.
#include <gtest/gtest.h>

#include <mrpt/maps/CSimpleMap.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement3D.h>
#include <mrpt/obs/CRawlog.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPose3DPDF.h>
#include <mrpt/poses/CPose3DPDFGaussian.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "gasp/core/tum_trajectory.h"
#include "gasp/rawlog/observation_conversion.h"
#include "depth_difference.h"
#include "gasp_test_data.h"
#include "program_run.h"

namespace {

using gasp::test::contains;
using gasp::test::countLinesStartingWith;
using gasp::test::medianAbsDifference;
using gasp::test::runProgram;

std::size_t printedCount(const std::string& output, const std::string& key) {
  const auto pos = output.find("\n" + key);
  return pos == std::string::npos ? static_cast<std::size_t>(-1) : std::stoul(output.substr(pos + 1 + key.size()));
}

/// A rawlog (format `format`) of the first `frames` of a simulated room at 5 Hz (by default 16
/// of 30, every one tracked) in DIR, with its ground truth beside it (DIR/sim_groundtruth.txt).
std::string simulatedRawlog(const std::string& dir, int format = 2, int frames = 16, int simulated_frames = 30,
                            const std::string& options = "") {
  auto run = runProgram("gasp-simulate", "--out " + dir + "/simdir --frames " + std::to_string(simulated_frames) + " --rate 5");
  EXPECT_EQ(run.exit_code, 0) << run.output;
  run = runProgram("gasp-tum2rawlog", "--no-rgb " + options + " --max-frames " + std::to_string(frames) + " --format " + std::to_string(format) + " " + dir + "/simdir " + dir +
                                          "/sim.rawlog");
  EXPECT_EQ(run.exit_code, 0) << run.output;
  return dir + "/sim.rawlog";
}

/// OUT/map.simplemap and OUT/traj.txt of a gasp-graphslam run with `nodes` nodes: node i of the
/// map is the scan the node was registered at (its timestamp), at the node's optimised robot
/// pose, which with the scan's own mounting gives the written camera trajectory.
void expectTheMapHoldsEachNodesScan(const std::string& out, std::size_t nodes) {
  const auto traj = gasp::readTumTrajectory(out + "/traj.txt");
  ASSERT_EQ(traj.size(), nodes);
  mrpt::maps::CSimpleMap map;
  ASSERT_TRUE(map.loadFromFile(out + "/map.simplemap"));
  ASSERT_EQ(map.size(), nodes);
  for (std::size_t i = 0; i < nodes; ++i) {
    const auto [pose, sf] = map.get(i);
    ASSERT_TRUE(pose && sf) << i;
    const auto scan = sf->getObservationByClass<mrpt::obs::CObservation3DRangeScan>();
    ASSERT_TRUE(scan) << i;
    const gasp::RgbdFrame frame = gasp::frameFromObservation(*scan, "map scan");
    EXPECT_NEAR(frame.timestamp, traj[i].timestamp, 1e-4) << i;
    const gasp::Isometry3 T_world_camera = gasp::fromCPose3D(pose->getMeanVal()) * frame.T_robot_camera;
    EXPECT_TRUE(T_world_camera.isApprox(traj[i].T_world_camera, 1e-4)) << i;
  }
}

/// OUT/odometry.rawlog: format #1, the first 16 scans of simulatedRawlog(OUT, 1), each preceded
/// by a CActionRobotMovement3D with the simulator's true robot motion since the previous scan
/// (none before the first); its ground truth is OUT/sim_groundtruth.txt.
void writeOdometryRawlog(const std::string& out, bool motion_in_steps_without_scans = false) {
  mrpt::obs::CRawlog plain, odometry;
  ASSERT_TRUE(plain.loadFromRawLogFile(simulatedRawlog(out, 1, 16)));
  const auto truth = gasp::readTumTrajectory(out + "/sim_groundtruth.txt");
  ASSERT_FALSE(truth.empty());
  const auto T_world_camera_at = [&](double t) {
    for (const auto& p : truth)
      if (std::abs(p.timestamp - t) < 1e-4) return std::optional<gasp::Isometry3>(p.T_world_camera);
    return std::optional<gasp::Isometry3>();
  };
  std::optional<gasp::Isometry3> previous;  // T_world_robot of the previous scan
  int moves = 0;
  for (std::size_t i = 0; i + 1 < plain.size(); i += 2) {
    ASSERT_EQ(plain.getType(i), mrpt::obs::CRawlog::etActionCollection) << i;
    const auto sf = plain.getAsObservations(i + 1);
    const auto scan = sf->getObservationByClass<mrpt::obs::CObservation3DRangeScan>();
    ASSERT_TRUE(scan) << i;
    const auto T_world_camera = T_world_camera_at(mrpt::Clock::toDouble(scan->timestamp));
    ASSERT_TRUE(T_world_camera) << i;
    // The optical camera's mounting (sensorPose and MRPT's fixed turn to the optical axes).
    const gasp::Isometry3 T_robot_camera = gasp::frameFromObservation(*scan, "odometry scan").T_robot_camera;
    const gasp::Isometry3 T_world_robot = *T_world_camera * T_robot_camera.inverse();
    mrpt::obs::CActionCollection actions;
    if (previous) {
      mrpt::obs::CActionRobotMovement3D move;
      move.poseChange.mean = gasp::toCPose3D(previous->inverse() * T_world_robot);
      move.poseChange.cov.setIdentity();
      move.poseChange.cov *= 1e-6;
      move.timestamp = scan->timestamp;  // the motion ends when the scan is taken
      actions.insert(move);
      ++moves;
    }
    if (motion_in_steps_without_scans && previous) {
      // The motion in a step of its own (an empty sensory frame), then the scan with no motion.
      mrpt::obs::CSensoryFrame nothing_seen;
      mrpt::obs::CActionCollection no_motion;
      odometry.insert(actions);
      odometry.insert(nothing_seen);
      odometry.insert(no_motion);
    } else {
      odometry.insert(actions);
    }
    odometry.insert(*sf);
    previous = T_world_robot;
  }
  ASSERT_EQ(moves, 15);
  ASSERT_TRUE(odometry.saveToRawLogFile(out + "/odometry.rawlog"));
}

/// OUT/fixed.ini: CFixedIntervalsNRD registers a node every 5 cm or 5 deg of odometry (MRPT's
/// defaults, 0.5 m / 60 deg, would give one or two nodes on the simulated rawlogs).
void writeFixedIntervalsIni(const std::string& out) {
  std::ofstream(out + "/fixed.ini") << "[NodeRegistrationDeciderParameters]\nregistration_max_distance = 0.05\n"
                                       "registration_max_angle = 5\n";
}

}  // namespace

TEST(GaspGraphSlamProgram, WritesTheTrajectoryGraphAndReports) {
  const std::string out = gasp::test::scratchDir();
  const std::string rawlog = simulatedRawlog(out);
  const auto run = runProgram("gasp-graphslam", "--rawlog " + rawlog + " --out " + out + "/traj.txt --graph " + out +
                                                    "/g.graph --report-dir " + out + "/report --gt " + out +
                                                    "/sim_groundtruth.txt");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_TRUE(contains(run.output, "\nscans: 16\n")) << run.output;
  EXPECT_TRUE(contains(run.output, "deciders: CGaspOdometryNRD, CGaspLoopClosureERD, CGaspPoseGraphGSO\n"));
  EXPECT_TRUE(contains(run.output, "\nbreak_edges: 0\n")) << run.output;
  const std::size_t nodes = printedCount(run.output, "nodes: "), edges = printedCount(run.output, "edges: ");
  ASSERT_GE(nodes, 2u) << run.output;
  ASSERT_LE(nodes, 16u) << run.output;
  EXPECT_EQ(countLinesStartingWith(out + "/g.graph", "VERTEX3 "), nodes);
  EXPECT_EQ(countLinesStartingWith(out + "/g.graph", "EDGE3 "), edges);
  EXPECT_EQ(gasp::readTumTrajectory(out + "/traj.txt").size(), nodes);
  for (const char* f : {"CGraphSlamEngine.log", "node_registrar.log", "edge_registrar.log", "optimizer.log", "timings.log"})
    EXPECT_TRUE(std::filesystem::exists(out + "/report/" + f)) << f;
  std::ifstream nrd_log(out + "/report/node_registrar.log");
  const std::string nrd_text((std::istreambuf_iterator<char>(nrd_log)), std::istreambuf_iterator<char>());
  EXPECT_TRUE(contains(nrd_text, "GASP depth odometry")) << nrd_text;
  // The nodes are within a centimetre of the simulator's truth.
  const auto pos = run.output.find("\nate_rmse_m: ");
  ASSERT_NE(pos, std::string::npos) << run.output;
  EXPECT_LT(std::stod(run.output.substr(pos + 13)), 0.01) << run.output;
  EXPECT_TRUE(contains(run.output, "\nmarginals_nees: median ")) << run.output;
}

TEST(GaspGraphSlamProgram, WritesAMapOfTheNodesScansAtTheirOptimisedPoses) {
  const std::string out = gasp::test::scratchDir();
  const std::string rawlog = simulatedRawlog(out);
  const auto run = runProgram("gasp-graphslam", "--rawlog " + rawlog + " --out " + out + "/traj.txt --simplemap " + out +
                                                    "/map.simplemap --cloud " + out + "/map.ply --voxel 0.02");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const std::size_t nodes = printedCount(run.output, "nodes: ");
  ASSERT_GE(nodes, 2u) << run.output;
  EXPECT_TRUE(contains(run.output, "simplemap: " + out + "/map.simplemap (" + std::to_string(nodes) + " nodes)"))
      << run.output;
  EXPECT_GT(printedCount(run.output, "cloud: " + out + "/map.ply ("), 1000u) << run.output;
  EXPECT_FALSE(contains(run.output, "warning")) << run.output;
  expectTheMapHoldsEachNodesScan(out, nodes);
  // Each node's pose carries its marginal covariance in the optimised graph: zero at the root,
  // centimetres further on.
  EXPECT_TRUE(contains(run.output, "marginals: " + std::to_string(nodes) + " nodes (")) << run.output;
  mrpt::maps::CSimpleMap map;
  ASSERT_TRUE(map.loadFromFile(out + "/map.simplemap"));
  const auto root = std::dynamic_pointer_cast<const mrpt::poses::CPose3DPDFGaussian>(std::get<0>(map.get(0)));
  const auto last = std::dynamic_pointer_cast<const mrpt::poses::CPose3DPDFGaussian>(std::get<0>(map.get(nodes - 1)));
  ASSERT_TRUE(root && last);
  EXPECT_EQ(root->cov.norm(), 0.0);
  EXPECT_GT(std::sqrt(last->cov(0, 0)), 0.01);  // a few centimetres after 16 scans (the model error)
  EXPECT_LT(std::sqrt(last->cov(0, 0)), 0.1);
  EXPECT_GT(std::sqrt(last->cov(3, 3)), 0.01);
  EXPECT_LT(std::sqrt(last->cov(3, 3)), 0.1);
  // Output folders are checked before the run.
  const auto bad = runProgram("gasp-graphslam", "--rawlog " + rawlog + " --cloud /nonexistent-dir/m.ply");
  EXPECT_EQ(bad.exit_code, 1) << bad.output;
  EXPECT_TRUE(contains(bad.output, "--cloud")) << bad.output;
  const auto voxel = runProgram("gasp-graphslam", "--rawlog " + rawlog + " --cloud " + out + "/m.ply --voxel 0");
  EXPECT_EQ(voxel.exit_code, 2) << voxel.output;
}

TEST(GaspGraphSlamProgram, WithTheDeskewTheMapHoldsTheDepthEachNodeWasRegisteredWith) {
  // rolling_shutter_readout_s: GASP's node decider deskews each scan before registering it (with
  // the last step's velocity; the first two scans have none). The map takes a deskewed
  // keyframe's depth as registered (keyframe_map.h); the root keeps the recorded one.
  const std::string out = gasp::test::scratchDir();
  const std::string rawlog = simulatedRawlog(out);
  mrpt::obs::CRawlog recorded;
  ASSERT_TRUE(recorded.loadFromRawLogFile(rawlog));
  std::ofstream(out + "/rs.ini") << "[CGaspOdometryNRD]\nrolling_shutter_readout_s = 0.03\n";
  const auto run = runProgram("gasp-graphslam", "--rawlog " + rawlog + " --ini " + out + "/rs.ini --out " + out +
                                                    "/traj.txt --simplemap " + out + "/map.simplemap");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const std::size_t nodes = printedCount(run.output, "nodes: ");
  ASSERT_GE(nodes, 4u) << run.output;
  expectTheMapHoldsEachNodesScan(out, nodes);  // timestamps and poses as without the deskew
  mrpt::maps::CSimpleMap map;
  ASSERT_TRUE(map.loadFromFile(out + "/map.simplemap"));
  std::size_t differ = 0;
  for (std::size_t i = 0; i < nodes; ++i) {
    const auto scan = std::get<1>(map.get(i))->getObservationByClass<mrpt::obs::CObservation3DRangeScan>();
    ASSERT_TRUE(scan) << i;
    // The rawlog's scan at the node's timestamp, and the one before it.
    mrpt::obs::CObservation3DRangeScan::Ptr original, before;
    for (std::size_t k = 0; k < recorded.size() && !original; ++k) {
      const auto o = recorded.getAsObservation(k);
      if (std::abs(mrpt::Clock::toDouble(o->timestamp) - mrpt::Clock::toDouble(scan->timestamp)) < 1e-6) {
        original = std::dynamic_pointer_cast<mrpt::obs::CObservation3DRangeScan>(o);
        if (k > 0) before = std::dynamic_pointer_cast<mrpt::obs::CObservation3DRangeScan>(recorded.getAsObservation(k - 1));
      }
    }
    ASSERT_TRUE(original) << i;
    ASSERT_EQ(scan->rangeImage.rows(), original->rangeImage.rows());
    ASSERT_EQ(scan->rangeImage.cols(), original->rangeImage.cols());
    int differing = 0;
    for (int r = 0; r < scan->rangeImage.rows(); ++r)
      for (int c = 0; c < scan->rangeImage.cols(); ++c) differing += scan->rangeImage(r, c) != original->rangeImage(r, c);
    if (i == 0) {
      EXPECT_EQ(differing, 0);
    }
    if (differing > scan->rangeImage.rows() * scan->rangeImage.cols() / 100) {
      ++differ;
      // This node's own depth moved by the deskew, not another scan's: the median difference
      // to its recording is well below the scan before's (measured 4-11 mm against 8-23 cm).
      ASSERT_TRUE(before) << i;
      const double own = medianAbsDifference(scan->rangeImage, original->rangeImage);
      const double previous = medianAbsDifference(scan->rangeImage, before->rangeImage);
      EXPECT_GE(own, 0.0) << i;
      EXPECT_LT(own, 0.5 * previous) << "node " << i << ": median |difference| " << own << " units to its recording, "
                                     << previous << " to the scan before's";
    }
  }
  EXPECT_GE(differ, nodes - 2) << "of " << nodes << " nodes";
}

TEST(GaspGraphSlamProgram, TheMapTakesTheScansOfTheDecidersSensor) {
  // Two depth sensors in every sensory frame, the other one first: with sensor_label = RGBD the
  // deciders use GASP's own scans, and so must the map (the other sensor's scans are 10 ms later).
  const std::string out = gasp::test::scratchDir();
  mrpt::obs::CRawlog one, two;
  ASSERT_TRUE(one.loadFromRawLogFile(simulatedRawlog(out, 1, 8)));
  for (std::size_t i = 0; i < one.size(); ++i) {
    if (one.getType(i) == mrpt::obs::CRawlog::etActionCollection) {
      two.insert(*one.getAsAction(i));
      continue;
    }
    const auto sf = one.getAsObservations(i);
    const auto scan = sf->getObservationByClass<mrpt::obs::CObservation3DRangeScan>();
    ASSERT_TRUE(scan);
    ASSERT_EQ(scan->sensorLabel, "RGBD");
    auto other = std::make_shared<mrpt::obs::CObservation3DRangeScan>(*scan);
    other->sensorLabel = "OTHER";
    other->timestamp = mrpt::Clock::fromDouble(mrpt::Clock::toDouble(scan->timestamp) + 0.01);
    mrpt::obs::CSensoryFrame both;
    both.insert(other);
    both.insert(scan);
    two.insert(both);
  }
  ASSERT_TRUE(two.saveToRawLogFile(out + "/two.rawlog"));
  std::ofstream(out + "/rgbd.ini") << "[CGaspOdometryNRD]\nsensor_label = RGBD\n[CGaspLoopClosureERD]\nsensor_label = RGBD\n";
  const auto run = runProgram("gasp-graphslam", "--rawlog " + out + "/two.rawlog --ini " + out + "/rgbd.ini --out " +
                                                    out + "/traj.txt --simplemap " + out + "/map.simplemap");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_TRUE(contains(run.output, "\nscans: 8\n")) << run.output;
  const auto traj = gasp::readTumTrajectory(out + "/traj.txt");
  mrpt::maps::CSimpleMap map;
  ASSERT_TRUE(map.loadFromFile(out + "/map.simplemap"));
  ASSERT_EQ(map.size(), traj.size());
  ASSERT_GE(traj.size(), 2u);
  for (std::size_t i = 0; i < traj.size(); ++i) {
    const auto [pose, sf] = map.get(i);
    ASSERT_TRUE(pose && sf) << i;
    const auto scan = sf->getObservationByClass<mrpt::obs::CObservation3DRangeScan>();
    ASSERT_TRUE(scan) << i;
    EXPECT_EQ(scan->sensorLabel, "RGBD") << i;
    EXPECT_NEAR(mrpt::Clock::toDouble(scan->timestamp), traj[i].timestamp, 1e-4) << i;
  }
}

TEST(GaspGraphSlamProgram, MapsWithMrptsOdometryNodeDecider) {
  // GASP's loop-closure decider and the map with MRPT's own node decider: CFixedIntervalsNRD
  // over a format-#1 rawlog whose actions carry the robot's motion (here the simulator's truth,
  // as CActionRobotMovement3D). The map must hold, for every node, the scan of the step that
  // registered it, at the node's pose.
  const std::string out = gasp::test::scratchDir();
  ASSERT_NO_FATAL_FAILURE(writeOdometryRawlog(out));
  writeFixedIntervalsIni(out);
  const auto run = runProgram("gasp-graphslam", "--rawlog " + out + "/odometry.rawlog --ini " + out +
                                                    "/fixed.ini --node-reg CFixedIntervalsNRD --out " + out +
                                                    "/traj.txt --simplemap " + out + "/map.simplemap --gt " + out +
                                                    "/sim_groundtruth.txt --graph " + out + "/g.graph");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  // MRPT's decider gives its first edge NaN information; the graph file has a break edge there.
  EXPECT_TRUE(contains(run.output, "warning: 1 edge(s) with non-finite information from the node decider written as break edges"))
      << run.output;
  std::ifstream graph_file(out + "/g.graph");
  const std::string graph_text((std::istreambuf_iterator<char>(graph_file)), std::istreambuf_iterator<char>());
  EXPECT_FALSE(contains(graph_text, "nan")) << graph_text;
  EXPECT_EQ(countLinesStartingWith(out + "/g.graph", "EDGE3 "), printedCount(run.output, "edges: "));
  EXPECT_TRUE(contains(run.output, "deciders: CFixedIntervalsNRD, CGaspLoopClosureERD, CGaspPoseGraphGSO\n")) << run.output;
  const std::size_t nodes = printedCount(run.output, "nodes: ");
  ASSERT_GE(nodes, 3u) << run.output;
  EXPECT_TRUE(contains(run.output, "simplemap: " + out + "/map.simplemap (" + std::to_string(nodes) + " nodes)"))
      << run.output;
  const auto pos = run.output.find("\nate_rmse_m: ");
  ASSERT_NE(pos, std::string::npos) << run.output;
  EXPECT_LT(std::stod(run.output.substr(pos + 13)), 0.01) << run.output;
  // The nodes' orientations as well (ATE compares positions only).
  const auto rpe = run.output.find("\nrpe_1s_rmse: ");
  ASSERT_NE(rpe, std::string::npos) << run.output;
  EXPECT_LT(std::stod(run.output.substr(rpe + 14)), 0.01) << run.output;
  const auto comma = run.output.find(", ", rpe);
  ASSERT_NE(comma, std::string::npos) << run.output;
  EXPECT_LT(std::stod(run.output.substr(comma + 2)), 0.5) << run.output;
  expectTheMapHoldsEachNodesScan(out, nodes);
}

TEST(GaspGraphSlamProgram, RunsRawlogsOfSensoryFramesAndMrptsOptimiser) {
  // Format #1 (sensory frames, no actions) and MRPT's CLevMarqGSO.
  const std::string out = gasp::test::scratchDir();
  const std::string rawlog = simulatedRawlog(out, 1);
  const auto run = runProgram("gasp-graphslam", "--rawlog " + rawlog + " --optimizer CLevMarqGSO --out " + out +
                                                    "/traj.txt");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_TRUE(contains(run.output, "\nscans: 16\n")) << run.output;
  EXPECT_TRUE(contains(run.output, "deciders: CGaspOdometryNRD, CGaspLoopClosureERD, CLevMarqGSO\n"));
  EXPECT_GE(printedCount(run.output, "nodes: "), 2u) << run.output;
}

TEST(GaspGraphSlamProgram, ListsItsClassesAndPrintsALoadableConfiguration) {
  const std::string out = gasp::test::scratchDir();
  auto run = runProgram("gasp-graphslam", "--list-regs");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_TRUE(contains(run.output, "CGaspOdometryNRD")) << run.output;
  EXPECT_TRUE(contains(run.output, "CGaspLoopClosureERD")) << run.output;
  EXPECT_TRUE(contains(run.output, "CFixedIntervalsNRD")) << run.output;  // MRPT's 3D-capable ones too
  for (const char* two_d_only : {"CICPCriteriaNRD", "CICPCriteriaERD", "CLoopCloserERD"})
    EXPECT_FALSE(contains(run.output, two_d_only)) << two_d_only << ": " << run.output;
  run = runProgram("gasp-graphslam", "--list-optimizers");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_TRUE(contains(run.output, "CGaspPoseGraphGSO")) << run.output;
  EXPECT_FALSE(contains(run.output, "CEmptyGSO")) << run.output;
  run = runProgram("gasp-graphslam", "--print-ini > " + out + "/printed.ini");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_EQ(countLinesStartingWith(out + "/printed.ini", "[CGaspPoseGraphGSO]"), 1u);
  // The printed configuration, edited, is what --ini reads.
  std::ofstream(out + "/printed.ini", std::ios::app) << "\n[CGaspOdometryNRD]\nkeyframe_distance_m = 0.3\n";
  run = runProgram("gasp-graphslam", "--rawlog " + simulatedRawlog(out) + " --ini " + out + "/printed.ini");
  EXPECT_EQ(run.exit_code, 0) << run.output;
}

TEST(GaspGraphSlamProgram, AnIniWithAFewKeysKeepsTheDefaultsOfTheRest) {
  // docs/graphslam.md's noloops.ini: one section, one key. The engine's own sections
  // ([GeneralConfiguration] ...) come from the built-in configuration, without MRPT's assertion.
  const std::string out = gasp::test::scratchDir();
  std::ofstream(out + "/noloops.ini") << "[CGaspLoopClosureERD]\nenabled = 0\n";
  const auto run = runProgram("gasp-graphslam", "--rawlog " + simulatedRawlog(out) + " --ini " + out + "/noloops.ini");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_FALSE(contains(run.output, "rawlog_seq_info")) << run.output;
  EXPECT_FALSE(contains(run.output, "xception")) << run.output;
  EXPECT_TRUE(contains(run.output, "\nloop_closures: 0")) << run.output;
  EXPECT_GE(printedCount(run.output, "nodes: "), 2u) << run.output;
}

TEST(GaspGraphSlamProgram, MaxScansStopsEarly) {
  const std::string out = gasp::test::scratchDir();
  const std::string rawlog = simulatedRawlog(out);
  const auto run = runProgram("gasp-graphslam", "--rawlog " + rawlog + " --max-scans 5 --out " + out + "/traj.txt");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_TRUE(contains(run.output, "\nscans: 5\n")) << run.output;
  EXPECT_LE(printedCount(run.output, "nodes: "), 5u) << run.output;
  EXPECT_EQ(runProgram("gasp-graphslam", "--rawlog " + rawlog + " --max-scans -1").exit_code, 2);
}

TEST(GaspGraphSlamProgram, FirstAndEveryThinTheScansAndKeepTheOdometry) {
  const std::string out = gasp::test::scratchDir();
  const auto truth_times = [&] {
    std::vector<double> t;
    for (const auto& p : gasp::readTumTrajectory(out + "/sim_groundtruth.txt")) t.push_back(p.timestamp);
    return t;
  };
  // Index of a node's timestamp among the simulator's frames (the rawlogs hold frames 0-15).
  const auto frameIndexOf = [](const std::vector<double>& times, double t) {
    for (std::size_t i = 0; i < times.size(); ++i)
      if (std::abs(times[i] - t) < 1e-4) return static_cast<int>(i);
    return -1;
  };
  // GASP's deciders, format #2: scans 1, 3, ..., 15 only; every node is one of them.
  const std::string rawlog = simulatedRawlog(out);
  const auto run = runProgram("gasp-graphslam", "--rawlog " + rawlog + " --first 1 --every 2 --out " + out + "/traj.txt");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_TRUE(contains(run.output, "\nscans: 8\nscans_not_used: 8 ")) << run.output;
  const auto times = truth_times();
  const auto traj = gasp::readTumTrajectory(out + "/traj.txt");
  ASSERT_GE(traj.size(), 2u) << run.output;
  for (const auto& p : traj) {
    const int i = frameIndexOf(times, p.timestamp);
    EXPECT_TRUE(i >= 1 && i % 2 == 1) << p.timestamp << " is frame " << i;
  }

  // MRPT's odometry node decider, format #1 with the true motion as actions: the motion of the
  // steps left out reaches the engine with the next step, so the nodes are still where the
  // simulator put the robot (a dropped motion would put every later node off by it).
  ASSERT_NO_FATAL_FAILURE(writeOdometryRawlog(out));
  writeFixedIntervalsIni(out);
  const auto odo = runProgram("gasp-graphslam", "--rawlog " + out + "/odometry.rawlog --ini " + out +
                                                    "/fixed.ini --node-reg CFixedIntervalsNRD --every 3 --out " + out +
                                                    "/traj3.txt --gt " + out + "/sim_groundtruth.txt");
  ASSERT_EQ(odo.exit_code, 0) << odo.output;
  EXPECT_TRUE(contains(odo.output, "\nscans: 6\nscans_not_used: 10 ")) << odo.output;
  const auto traj3 = gasp::readTumTrajectory(out + "/traj3.txt");
  ASSERT_GE(traj3.size(), 3u) << odo.output;
  for (const auto& p : traj3) {
    const int i = frameIndexOf(times, p.timestamp);
    EXPECT_TRUE(i >= 0 && i % 3 == 0) << p.timestamp << " is frame " << i;
  }
  const auto ate = odo.output.find("\nate_rmse_m: ");
  ASSERT_NE(ate, std::string::npos) << odo.output;
  EXPECT_LT(std::stod(odo.output.substr(ate + 13)), 0.01) << odo.output;

  // The motion in steps of their own, without a scan: MRPT's decider registers its nodes there.
  // Such a node has the step's time and the mounting of the scans; GASP's loop closer gives it no
  // view (not an earlier scan, which was taken elsewhere).
  ASSERT_NO_FATAL_FAILURE(writeOdometryRawlog(out, true));
  const auto apart = runProgram("gasp-graphslam", "--rawlog " + out + "/odometry.rawlog --ini " + out +
                                                      "/fixed.ini --node-reg CFixedIntervalsNRD --out " + out +
                                                      "/traj_apart.txt --gt " + out + "/sim_groundtruth.txt");
  ASSERT_EQ(apart.exit_code, 0) << apart.output;
  const auto traj_apart = gasp::readTumTrajectory(out + "/traj_apart.txt");
  ASSERT_GE(traj_apart.size(), 3u) << apart.output;
  for (const auto& p : traj_apart) EXPECT_GE(frameIndexOf(times, p.timestamp), 0) << p.timestamp;
  const auto ate_apart = apart.output.find("\nate_rmse_m: ");
  ASSERT_NE(ate_apart, std::string::npos) << apart.output;
  EXPECT_LT(std::stod(apart.output.substr(ate_apart + 13)), 0.01) << apart.output;

  // Bad selections: a usage error, or an error that says how many scans there are.
  EXPECT_EQ(runProgram("gasp-graphslam", "--rawlog " + rawlog + " --every 0").exit_code, 2);
  EXPECT_EQ(runProgram("gasp-graphslam", "--rawlog " + rawlog + " --first -1").exit_code, 2);
  const auto beyond = runProgram("gasp-graphslam", "--rawlog " + rawlog + " --first 16");
  EXPECT_EQ(beyond.exit_code, 1) << beyond.output;
  EXPECT_TRUE(contains(beyond.output, "--first 16 is beyond its 16 scans")) << beyond.output;
}

TEST(GaspGraphSlamProgram, FindsImagesStoredBesideTheRawlog) {
  // gasp-tum2rawlog --external: the depth images in sim_Images/, found from any working directory.
  const std::string out = gasp::test::scratchDir();
  const std::string rawlog = simulatedRawlog(out, 2, 8, 30, "--external");
  ASSERT_TRUE(std::filesystem::exists(out + "/sim_Images"));
  const auto run = runProgram("gasp-graphslam", "--rawlog " + rawlog);
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_GE(printedCount(run.output, "nodes: "), 2u) << run.output;
  EXPECT_FALSE(contains(run.output, "skipped_scans")) << run.output;

  // One scan's image file gone: that scan is skipped with a warning, the rest is written, and
  // the exit code (3) says the result is incomplete.
  std::vector<std::string> images;
  for (const auto& e : std::filesystem::directory_iterator(out + "/sim_Images"))
    if (e.path().filename().string().find("_depth.bin") != std::string::npos) images.push_back(e.path().string());
  ASSERT_GE(images.size(), 8u);
  std::sort(images.begin(), images.end());
  std::filesystem::remove(images[4]);
  const auto gap = runProgram("gasp-graphslam", "--rawlog " + rawlog + " --out " + out + "/t.txt");
  EXPECT_EQ(gap.exit_code, 3) << gap.output;
  EXPECT_TRUE(contains(gap.output, "\nskipped_scans: 1\n")) << gap.output;
  EXPECT_TRUE(contains(gap.output, "warning: 1 scans could not be converted")) << gap.output;
  EXPECT_TRUE(std::filesystem::exists(out + "/t.txt"));
}

TEST(GaspGraphSlamProgram, StandardOutputHoldsOnlyItsOwnLines) {
  // MRPT's engine and deciders log to stdout ("[time|INFO |CGraphSlamEngine] ...", the time
  // logger's table): sent to stderr, so stdout is the program's "key: value" lines alone.
  const std::string out = gasp::test::scratchDir();
  const auto run = runProgram("gasp-graphslam", "--rawlog " + simulatedRawlog(out), "/dev/null");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  std::istringstream lines(run.output);
  std::size_t n = 0;
  for (std::string line; std::getline(lines, line); ++n)
    EXPECT_TRUE(line.find(": ") != std::string::npos && line[0] != '[' && line[0] != ' ' && line[0] != '-') << line;
  EXPECT_GE(n, 6u) << run.output;
  EXPECT_TRUE(contains(run.output, "\nnodes: ")) << run.output;
}

TEST(GaspGraphSlamProgram, SaysWhenTrackingWasLost) {
  // The room simulated in 20 frames moves faster, and the occluder pops in: with the node
  // decider's scene-change attempt off (scene_change = 0) that frame is not tracked and the node
  // decider inserts a break edge; exit 3, and the outputs are still written.
  const std::string out = gasp::test::scratchDir();
  const std::string rawlog = simulatedRawlog(out, 2, 20, 20);
  std::ofstream(out + "/no_scene_change.ini") << "[CGaspOdometryNRD]\nscene_change = 0\n";
  auto run = runProgram("gasp-graphslam", "--rawlog " + rawlog + " --ini " + out + "/no_scene_change.ini --out " + out +
                                              "/t.txt");
  EXPECT_EQ(run.exit_code, 3) << run.output;
  EXPECT_TRUE(contains(run.output, "\nbreak_edges: 1\n")) << run.output;
  EXPECT_EQ(gasp::readTumTrajectory(out + "/t.txt").size(), printedCount(run.output, "nodes: "));
  // By default the frame is taken through the scene change (docs/odometry.md): no break edge.
  run = runProgram("gasp-graphslam", "--rawlog " + rawlog + " --out " + out + "/t2.txt");
  EXPECT_EQ(run.exit_code, 0) << run.output;
  EXPECT_TRUE(contains(run.output, "\nbreak_edges: 0\n")) << run.output;
}

TEST(GaspGraphSlamProgram, BadInputGivesExitCodesAndReasons) {
  const std::string out = gasp::test::scratchDir();
  auto run = runProgram("gasp-graphslam", "--rawlog " + out + "/missing.rawlog");
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_TRUE(contains(run.output, "cannot open rawlog")) << run.output;
  run = runProgram("gasp-graphslam", "");
  EXPECT_EQ(run.exit_code, 2) << run.output;
  const std::string rawlog = simulatedRawlog(out);
  // A cut file is an error, not a shorter sequence (MRPT's own rawlog loop ends there quietly).
  std::filesystem::copy_file(rawlog, out + "/cut.rawlog");
  std::filesystem::resize_file(out + "/cut.rawlog", std::filesystem::file_size(rawlog) * 2 / 3);
  run = runProgram("gasp-graphslam", "--rawlog " + out + "/cut.rawlog");
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_TRUE(contains(run.output, "cut.rawlog") && contains(run.output, "truncated")) << run.output;
  run = runProgram("gasp-graphslam", "--rawlog " + rawlog + " --node-reg CICPCriteriaNRD");
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_TRUE(contains(run.output, "no node registration decider 'CICPCriteriaNRD'")) << run.output;
  run = runProgram("gasp-graphslam", "--rawlog " + rawlog + " --optimizer CEmptyGSO");
  EXPECT_EQ(run.exit_code, 2) << run.output;
  run = runProgram("gasp-graphslam", "--rawlog " + rawlog + " --ini " + out + "/missing.ini");
  EXPECT_EQ(run.exit_code, 1) << run.output;
  std::ofstream(out + "/garbage.ini") << "not an ini file\n";
  run = runProgram("gasp-graphslam", "--rawlog " + rawlog + " --ini " + out + "/garbage.ini");
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_TRUE(contains(run.output, "garbage.ini:1: neither a [section]")) << run.output;
  std::ofstream(out + "/bad.ini") << "[CGaspLoopClosureERD]\nsearch_radius = 0.5\n";
  run = runProgram("gasp-graphslam", "--rawlog " + rawlog + " --ini " + out + "/bad.ini");
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_TRUE(contains(run.output, "search_radius")) << run.output;
  // One scan: one keyframe, no graph.
  run = runProgram("gasp-graphslam", "--rawlog " + simulatedRawlog(out, 2, 1));
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_TRUE(contains(run.output, "no graph")) << run.output;
  // Not a rawlog; an empty file.
  std::ofstream(out + "/garbage.rawlog") << "this is not a rawlog at all, just text\n";
  run = runProgram("gasp-graphslam", "--rawlog " + out + "/garbage.rawlog");
  EXPECT_EQ(run.exit_code, 1) << run.output;
  std::ofstream(out + "/empty.rawlog").close();
  run = runProgram("gasp-graphslam", "--rawlog " + out + "/empty.rawlog");
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_TRUE(contains(run.output, "empty file")) << run.output;
}

TEST(GaspGraphSlamProgram, ClosesLoopsOnFr1Xyz) {
  GASP_REQUIRE_DATA(dir, "tum/fr1_xyz");
  const std::string out = gasp::test::scratchDir();
  auto run = runProgram("gasp-tum2rawlog", "--no-rgb --max-frames 240 " + dir + " " + out + "/xyz.rawlog");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  run = runProgram("gasp-graphslam", "--rawlog " + out + "/xyz.rawlog --gt " + out + "/xyz_groundtruth.txt --graph " +
                                         out + "/g.graph");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  std::printf("%s", run.output.substr(run.output.find("\nrawlog_entries")).c_str());
  const std::size_t loops = printedCount(run.output, "loop_closures: ");
  EXPECT_GE(loops, 5u) << run.output;
  EXPECT_LT(loops, 1000u) << run.output;
  EXPECT_EQ(countLinesStartingWith(out + "/g.graph", "EDGE3 "), printedCount(run.output, "edges: "));
  const auto pos = run.output.find("\nate_rmse_m: ");
  ASSERT_NE(pos, std::string::npos) << run.output;
  EXPECT_LT(std::stod(run.output.substr(pos + 13)), 0.02) << run.output;
}
