// GASP's mrpt::graphslam classes in CGraphSlamEngine (gasp/graphslam): a synthetic loop with exact
// ground truth through the engine, relocalisation after a break, bad scans, the optimiser's
// removal of a contradicted closure, the options checker and the ini sections.
#include <gtest/gtest.h>

#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement3D.h>
#include <mrpt/obs/CSensoryFrame.h>

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "gasp/core/error.h"
#include "gasp/eval/ate.h"
#include "gasp/graphslam/CGaspLoopClosureERD.h"
#include "gasp/graphslam/CGaspOdometryNRD.h"
#include "gasp/graphslam/CGaspPoseGraphGSO.h"
#include "gasp/graphslam/engine.h"
#include "gasp/graphslam/ini_check.h"
#include "gasp/graphslam/options_checker.h"
#include "gasp/graphslam/rawlog_run.h"
#include "gasp/graphslam/scan_selection.h"
#include "gasp/rawlog/observation_conversion.h"
#include "gasp/rawlog/rawlog_entries.h"
#include "gasp/rawlog/rawlog_writer.h"
#include "gasp_test_data.h"
#include "loop_sequence.h"

namespace {

using gasp::Isometry3;
using gasp::graphslam::Graph3D;

const char* const kEngineSections =
    "[GeneralConfiguration]\nclass_verbosity = 3\n"
    "[VisualizationParameters]\nvisualize_map = 0\nvisualize_odometry_poses = 0\n"
    "visualize_estimated_trajectory = 0\nvisualize_ground_truth = 0\nvisualize_SLAM_metric = 0\n"
    "enable_curr_pos_viewport = 0\n"
    "[CGaspOdometryNRD]\nclass_verbosity = 3\n[CGaspLoopClosureERD]\nclass_verbosity = 3\n"
    "[CGaspPoseGraphGSO]\nclass_verbosity = 3\n";

std::string writeFile(const std::string& path, const std::string& text) {
  std::ofstream(path) << text;
  return path;
}

/// An MRPT-like mounting: the optical axis along the robot's x, 0.3 m up.
Isometry3 mounting() {
  Isometry3 S = Isometry3::Identity();
  S.linear() << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  S.translation() = Eigen::Vector3d(0.1, 0.0, 0.3);
  return S;
}

mrpt::obs::CObservation3DRangeScan::Ptr scanOf(const gasp::test::LoopSequence& s, std::size_t i) {
  gasp::RgbdFrame f;
  f.timestamp = s.timestamps[i];
  f.depth_m = s.depth[i];
  f.depth_intrinsics = s.K;
  f.T_robot_camera = mounting();
  return gasp::observationFromFrame(f);
}

/// The three GASP classes in an engine.
struct GaspEngine {
  gasp::graphslam::CGaspOdometryNRD nrd;
  gasp::graphslam::CGaspLoopClosureERD erd;
  gasp::graphslam::CGaspPoseGraphGSO gso;
  std::unique_ptr<gasp::graphslam::GraphSlamEngine> engine;
  std::size_t entry = 0;

  explicit GaspEngine(const std::string& ini)
      : engine(gasp::graphslam::makeGraphSlamEngine(ini, "", nrd, erd, gso)) {}

  /// Rawlog format #2: the observation alone.
  void step(const mrpt::obs::CObservation::Ptr& obs) {
    mrpt::obs::CActionCollection::Ptr action;
    mrpt::obs::CSensoryFrame::Ptr sf;
    mrpt::obs::CObservation::Ptr o = obs;
    engine->_execGraphSlamStep(action, sf, o, entry);
    ++entry;
  }
  /// Rawlog format #1: an empty action and a sensory frame holding the observation.
  void stepAsSensoryFrame(const mrpt::obs::CObservation::Ptr& obs) {
    auto action = gasp::graphslam::noMotionAction();
    auto sf = std::make_shared<mrpt::obs::CSensoryFrame>();
    sf->insert(obs);
    mrpt::obs::CObservation::Ptr none;
    engine->_execGraphSlamStep(action, sf, none, entry);
    ++entry;
  }
  const Graph3D& graph() const { return engine->getGraph(); }
};

/// n nodes 0.1 m apart along x, no edges.
Graph3D nodesAlongX(int n) {
  Graph3D graph;
  for (int i = 0; i < n; ++i) graph.nodes[i] = mrpt::poses::CPose3D(0.1 * i, 0, 0, 0, 0, 0);
  return graph;
}

/// An edge of `dx` metres along x with `information` on every axis.
mrpt::poses::CPose3DPDFGaussianInf edgeAlongX(double dx, double information) {
  mrpt::poses::CPose3DPDFGaussianInf e;
  e.mean = mrpt::poses::CPose3D(dx, 0, 0, 0, 0, 0);
  e.cov_inv.setIdentity();
  e.cov_inv *= information;
  return e;
}

/// The truth of node i: the camera pose of its odometry frame.
Isometry3 truthOfNode(const GaspEngine& e, const gasp::test::LoopSequence& s, std::size_t node) {
  return s.T_world_camera[e.nrd.nodeFrames()[node]];
}

/// Every edge between non-consecutive nodes is a true loop closure (robot frames, within 2 cm and
/// 1 deg); returns the longest one's span in nodes.
std::size_t expectTrueClosures(const GaspEngine& e, const gasp::test::LoopSequence& s) {
  const Isometry3 S_inv = mounting().inverse();
  std::size_t longest = 0;
  for (const auto& [ids, edge] : e.graph().edges) {
    const auto [from, to] = ids;
    if (to == from + 1) continue;
    longest = std::max<std::size_t>(longest, to - from);
    const Isometry3 truth = (truthOfNode(e, s, from) * S_inv).inverse() * (truthOfNode(e, s, to) * S_inv);
    const Isometry3 err = truth.inverse() * gasp::fromCPose3D(edge.mean);
    EXPECT_LT(gasp::translationNorm(err), 0.02) << from << " -> " << to;
    EXPECT_LT(gasp::rotationAngle(err) * 180 / M_PI, 1.0) << from << " -> " << to;
  }
  return longest;
}

}  // namespace

TEST(GraphSlamEngine, ClosesTheLoopOfACircleWithGaspsDecidersAndOptimises) {
  const std::string dir = gasp::test::scratchDir();
  const auto s = gasp::test::circleSequence(30);
  GaspEngine e(writeFile(dir + "/g.ini", kEngineSections));
  for (std::size_t i = 0; i < s.depth.size(); ++i) e.step(scanOf(s, i));
  e.gso.optimizeNow();

  ASSERT_NE(e.nrd.odometry(), nullptr);
  EXPECT_EQ(e.nrd.odometry()->trackedCount(), 30u);
  EXPECT_EQ(e.nrd.breakEdges(), 0u);
  EXPECT_EQ(e.nrd.skippedScans(), 0u);
  const std::size_t n = e.graph().nodeCount();
  EXPECT_EQ(n, e.nrd.odometry()->keyframeCount());
  ASSERT_EQ(n, e.nrd.nodeFrames().size());
  ASSERT_GE(n, 5u);
  ASSERT_GE(e.erd.insertedEdges(), 1u);
  EXPECT_EQ(e.graph().edgeCount(), n - 1 + e.erd.insertedEdges() - e.gso.droppedEdges());

  // Every edge between non-consecutive nodes is a true loop closure (robot frames).
  EXPECT_GE(expectTrueClosures(e, s), n / 2) << "a closure spans much of the circle";

  // The root stays at the world's origin (the first robot frame); the optimised nodes are within
  // a centimetre of the truth and no worse than the odometry's keyframes.
  EXPECT_TRUE(gasp::fromCPose3D(e.graph().nodes.at(0)).isApprox(Isometry3::Identity(), 1e-6));
  gasp::Trajectory gt, optimised, odometry;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t f = e.nrd.nodeFrames()[i];
    gt.push_back({s.timestamps[f], s.T_world_camera[f]});
    optimised.push_back({s.timestamps[f], gasp::fromCPose3D(e.graph().nodes.at(i)) * mounting()});
    odometry.push_back({s.timestamps[f], e.nrd.odometry()->frames()[f].T_world_camera});
  }
  const double ate = gasp::eval::computeAte(gt, optimised).translation.rmse;
  const double ate_odo = gasp::eval::computeAte(gt, odometry).translation.rmse;
  std::printf("engine, circle of 30 frames: %zu nodes, %zu loop closures of %zu tried, %zu optimisations; node ATE "
              "%.4f m (odometry %.4f m)\n",
              n, e.erd.insertedEdges(), e.erd.attempts().size(), e.gso.optimisations(), ate, ate_odo);
  EXPECT_LT(ate, 0.01);
  EXPECT_LE(ate, ate_odo + 1e-4);
  EXPECT_GE(e.gso.optimisations(), 2u);  // during the run (after closures) and at the end
}

TEST(GraphSlamEngine, ClosesTheCircleByPlaceRetrievalToo) {
  // loop_search = retrieval in the loop closer's section: candidates by the nodes' place
  // descriptors alone (as DepthSlam's), every closure true, the end found back at the start.
  const std::string dir = gasp::test::scratchDir();
  const auto s = gasp::test::circleSequence(30);
  std::string ini = kEngineSections;
  ini.replace(ini.find("[CGaspLoopClosureERD]\n"), std::string("[CGaspLoopClosureERD]\n").size(),
              "[CGaspLoopClosureERD]\nloop_search = retrieval\n");
  GaspEngine e(writeFile(dir + "/g.ini", ini));
  for (std::size_t i = 0; i < s.depth.size(); ++i) e.step(scanOf(s, i));
  e.gso.optimizeNow();
  const std::size_t n = e.graph().nodeCount();
  ASSERT_GE(e.erd.insertedEdges(), 1u);
  EXPECT_GE(expectTrueClosures(e, s), n / 2) << "a closure spans much of the circle";
}

TEST(CGaspLoopClosureERD, TakesTheNodeDecidersKeyframeViewsInsteadOfSegmentingAgain) {
  // Linked to GASP's node decider (as gasp-graphslam does), the loop closer segments nothing and
  // tries and takes the same closures with the same inliers as when it segments each scan itself.
  const std::string dir = gasp::test::scratchDir();
  const auto s = gasp::test::circleSequence(30);
  const std::string ini = writeFile(dir + "/g.ini", kEngineSections);
  GaspEngine own(ini), linked(ini);
  linked.erd.useKeyframeViewsOf(&linked.nrd);
  for (std::size_t i = 0; i < s.depth.size(); ++i) {
    own.step(scanOf(s, i));
    linked.step(scanOf(s, i));
  }
  ASSERT_EQ(linked.graph().nodeCount(), own.graph().nodeCount());
  EXPECT_GE(own.erd.segmentations(), own.graph().nodeCount());
  EXPECT_EQ(linked.erd.segmentations(), 0u);
  ASSERT_EQ(linked.erd.attempts().size(), own.erd.attempts().size());
  ASSERT_GE(own.erd.insertedEdges(), 1u);
  for (std::size_t k = 0; k < own.erd.attempts().size(); ++k) {
    const auto &a = own.erd.attempts()[k], &b = linked.erd.attempts()[k];
    EXPECT_EQ(b.from, a.from) << k;
    EXPECT_EQ(b.to, a.to) << k;
    EXPECT_EQ(b.accepted, a.accepted) << k;
    EXPECT_EQ(b.inliers, a.inliers) << k;
  }
  // The newest node's view is the odometry's keyframe view itself (its buffers, not a copy).
  const std::size_t last = linked.graph().nodeCount() - 1;
  ASSERT_NE(linked.erd.nodeView(last), nullptr);
  EXPECT_EQ(linked.erd.nodeView(last)->segmentation.labels.data, linked.nrd.odometry()->keyframeView()->segmentation.labels.data);
  ASSERT_NE(own.erd.nodeView(last), nullptr);
  EXPECT_NE(own.erd.nodeView(last)->segmentation.labels.data, own.nrd.odometry()->keyframeView()->segmentation.labels.data);

  // With the rolling-shutter deskew, the loop closer gets the deskewed keyframe views.
  std::string deskew_sections = kEngineSections;
  const std::string nrd_section = "[CGaspOdometryNRD]\nclass_verbosity = 3\n";
  deskew_sections.replace(deskew_sections.find(nrd_section), nrd_section.size(),
                          nrd_section + "rolling_shutter_readout_s = 0.03\n");
  // (On the heap: five engines' deciders exceed the test thread's stack.)
  const auto deskewed_engine = std::make_unique<GaspEngine>(writeFile(dir + "/deskew.ini", deskew_sections));
  GaspEngine& deskewed = *deskewed_engine;
  deskewed.erd.useKeyframeViewsOf(&deskewed.nrd);
  for (std::size_t i = 0; i < 10; ++i) deskewed.step(scanOf(s, i));
  const std::size_t newest = deskewed.graph().nodeCount() - 1;
  ASSERT_GE(newest, 1u);
  EXPECT_TRUE(deskewed.nrd.odometry()->frames()[deskewed.nrd.nodeFrames()[newest]].deskewed);
  ASSERT_NE(deskewed.erd.nodeView(newest), nullptr);
  EXPECT_EQ(deskewed.erd.nodeView(newest)->segmentation.labels.data,
            deskewed.nrd.odometry()->keyframeView()->segmentation.labels.data);
  EXPECT_EQ(deskewed.erd.segmentations(), 0u);

  // Another sensor label than the node decider's: the loop closer segments its own sensor's scans.
  const auto labelled_engine = std::make_unique<GaspEngine>(ini);
  GaspEngine& labelled = *labelled_engine;
  labelled.erd.useKeyframeViewsOf(&labelled.nrd);
  labelled.erd.setSensorLabel("OTHER");
  for (std::size_t i = 0; i < 10; ++i) labelled.step(scanOf(s, i));
  EXPECT_EQ(labelled.erd.segmentations(), 0u);  // no scan of its sensor: nothing, not the node decider's
  ASSERT_GE(labelled.graph().nodeCount(), 2u);
  EXPECT_EQ(labelled.erd.nodeView(labelled.graph().nodeCount() - 1), nullptr);

  // Other segmentation parameters than the node decider's: the loop closer segments itself.
  const auto other_engine = std::make_unique<GaspEngine>(ini);
  GaspEngine& other = *other_engine;
  other.erd.useKeyframeViewsOf(&other.nrd);
  gasp::PairParams pair = other.erd.pairParams();
  pair.segment.target_patch_area_m2 *= 1.5;
  other.erd.setParams(pair, other.erd.loopParams());
  for (std::size_t i = 0; i < 8; ++i) other.step(scanOf(s, i));
  EXPECT_GE(other.erd.segmentations(), other.graph().nodeCount());
  EXPECT_GE(other.graph().nodeCount(), 2u);
}

TEST(GraphSlamEngine, ReadsSensoryFramesAsWellAsObservations) {
  const std::string dir = gasp::test::scratchDir();
  const auto s = gasp::test::circleSequence(30);
  GaspEngine e(writeFile(dir + "/g.ini", kEngineSections));
  for (std::size_t i = 0; i < 8; ++i) e.stepAsSensoryFrame(scanOf(s, i));
  ASSERT_NE(e.nrd.odometry(), nullptr);
  EXPECT_EQ(e.nrd.odometry()->frames().size(), 8u);
  EXPECT_EQ(e.graph().nodeCount(), e.nrd.odometry()->keyframeCount());
  EXPECT_GE(e.graph().nodeCount(), 2u);
}

TEST(GraphSlamEngine, RelocalisesAcrossABreakAndKeepsTheLookAwayNodesApart) {
  // Frames 12-14 look away: the odometry loses track into that view and back, so the node
  // decider inserts break edges; the loop closer relocalises the later nodes.
  const std::string dir = gasp::test::scratchDir();
  const auto s = gasp::test::circleSequence(30, {12, 13, 14});
  GaspEngine e(writeFile(dir + "/g.ini", kEngineSections));
  for (std::size_t i = 0; i < s.depth.size(); ++i) e.step(scanOf(s, i));
  e.gso.optimizeNow();
  EXPECT_GE(e.nrd.breakEdges(), 1u);
  const auto looksAway = [&](std::size_t node) {
    const std::size_t f = e.nrd.nodeFrames()[node];
    return f >= 12 && f <= 14;
  };
  std::size_t relocalisations = 0;
  for (const auto& a : e.erd.attempts()) {
    if (!a.accepted) continue;
    relocalisations += a.relocalisation ? 1 : 0;
    EXPECT_EQ(looksAway(a.from), looksAway(a.to)) << a.from << " -> " << a.to;
  }
  EXPECT_GE(relocalisations, 2u);  // two agreeing votes
  // After the relocalisation, the last node is where it truly is relative to the root.
  const std::size_t last = e.graph().nodeCount() - 1;
  const Isometry3 S_inv = mounting().inverse();
  const Isometry3 truth = (truthOfNode(e, s, 0) * S_inv).inverse() * (truthOfNode(e, s, last) * S_inv);
  const Isometry3 err = truth.inverse() * gasp::fromCPose3D(e.graph().nodes.at(last));
  EXPECT_LT(gasp::translationNorm(err), 0.03);
  EXPECT_LT(gasp::rotationAngle(err) * 180 / M_PI, 2.0);
}

TEST(GraphSlamEngine, BadScansAreSkippedWithoutStoppingTheRun) {
  const std::string dir = gasp::test::scratchDir();
  const auto s = gasp::test::circleSequence(30);
  GaspEngine e(writeFile(dir + "/g.ini", kEngineSections));
  // No depth at all: no patches, no node, no crash.
  auto empty = scanOf(s, 0);
  empty->rangeImage.fill(0);
  e.step(empty);
  for (std::size_t i = 1; i < 6; ++i) e.step(scanOf(s, i));
  // A range image whose size disagrees with the camera; then a timestamp that goes backwards.
  auto wrong_size = scanOf(s, 6);
  wrong_size->rangeImage.resize(10, 10);
  e.step(wrong_size);
  e.step(scanOf(s, 2));
  for (std::size_t i = 6; i < 10; ++i) e.step(scanOf(s, i));
  EXPECT_EQ(e.nrd.skippedScans(), 2u);
  ASSERT_NE(e.nrd.odometry(), nullptr);
  EXPECT_EQ(e.nrd.odometry()->frames().size(), 10u);  // the empty frame, 1-5 and 6-9
  EXPECT_GE(e.graph().nodeCount(), 2u);
}

TEST(GraphSlamEngine, StartsWithoutWaitingForAKeyPress) {
  // MRPT 2.5.8's constructor pauses for a key; with a standard input that stays open and never
  // delivers one (an idle pipe), makeGraphSlamEngine() must still return.
  const std::string dir = gasp::test::scratchDir();
  int fds[2];
  ASSERT_EQ(::pipe(fds), 0);
  const int saved = ::dup(0);
  ::dup2(fds[0], 0);
  {
    GaspEngine e(writeFile(dir + "/g.ini", kEngineSections));
    EXPECT_EQ(e.graph().nodeCount(), 0u);
  }
  ::dup2(saved, 0);
  ::close(saved);
  ::close(fds[0]);
  ::close(fds[1]);
}

TEST(CGaspPoseGraphGSO, RemovesAContradictedClosureAndKeepsAConsistentOne) {
  // Six nodes 0.1 m apart along x; a closure 0 -> 5 that agrees and one 1 -> 4 that is 0.5 m off.
  Graph3D graph = nodesAlongX(6);
  for (int i = 0; i < 5; ++i) graph.insertEdge(i, i + 1, edgeAlongX(0.1, 1e4));
  graph.insertEdge(0, 5, edgeAlongX(0.5, 1e4));
  graph.insertEdge(1, 4, edgeAlongX(0.8, 1e4));
  gasp::graphslam::CGaspPoseGraphGSO gso;
  gso.setGraphPtr(&graph);
  gso.optimizeNow();
  EXPECT_EQ(gso.droppedEdges(), 1u);
  EXPECT_EQ(graph.edges.count({1, 4}), 0u);
  EXPECT_EQ(graph.edges.count({0, 5}), 1u);
  EXPECT_EQ(graph.edgeCount(), 6u);
  EXPECT_NEAR(graph.nodes.at(5).x(), 0.5, 1e-6);
  EXPECT_NEAR(graph.nodes.at(0).x(), 0.0, 1e-12);  // the gauge: node 0 fixed
  EXPECT_LT(gso.lastResult().final_chi2, 1e-6);
}

TEST(CGaspPoseGraphGSO, RemovesAContradictedSecondEdgeBetweenConsecutiveNodesButNotTheFirst) {
  // Nodes 0.1 m apart along x. Between 2 and 3 the node decider's break edge comes first, then a
  // relocalisation 0.4 m off; a closure 0 -> 5 agrees with the odometry. Between 3 and 4 the
  // node decider's edge itself is off: it is no closure, so it stays.
  Graph3D graph = nodesAlongX(6);
  for (int i = 0; i < 5; ++i)
    graph.insertEdge(i, i + 1, edgeAlongX(i == 3 ? 0.102 : 0.1, i == 2 ? gasp::graphslam::kBreakInformation : 1e4));
  graph.insertEdge(2, 3, edgeAlongX(0.5, 1e4));
  graph.insertEdge(0, 5, edgeAlongX(0.502, 1e4));
  EXPECT_FALSE(gasp::graphslam::isClosureEdge(graph, graph.edges.find({3, 4})));
  EXPECT_TRUE(gasp::graphslam::isClosureEdge(graph, std::prev(graph.edges.equal_range({2, 3}).second)));
  EXPECT_FALSE(gasp::graphslam::isClosureEdge(graph, graph.edges.equal_range({2, 3}).first));
  EXPECT_TRUE(gasp::graphslam::isClosureEdge(graph, graph.edges.find({0, 5})));
  gasp::graphslam::CGaspPoseGraphGSO gso;
  gso.setGraphPtr(&graph);
  gso.optimizeNow();
  EXPECT_EQ(gso.droppedEdges(), 1u);
  ASSERT_EQ(graph.edges.count({2, 3}), 1u);
  EXPECT_TRUE(gasp::graphslam::isBreakEdge(graph.edges.find({2, 3})->second));
  EXPECT_EQ(graph.edges.count({3, 4}), 1u);
  EXPECT_EQ(graph.edges.count({0, 5}), 1u);
  EXPECT_EQ(graph.edgeCount(), 6u);
}

TEST(CGaspPoseGraphGSO, OptimisesAgainWhenAnEdgeIsRemoved) {
  // A loop closer that takes edges out of the graph (the rest of a relocalisation group) leaves
  // poses optimised with them: the optimiser runs again at its next step without a new node,
  // even when a closure was added in the same step.
  Graph3D graph = nodesAlongX(5);
  for (int i = 0; i < 4; ++i) graph.insertEdge(i, i + 1, edgeAlongX(0.1, 1e4));
  graph.insertEdge(0, 2, edgeAlongX(0.2, 1e4));
  gasp::graphslam::CGaspPoseGraphGSO gso;
  gso.setGraphPtr(&graph);
  const auto step = [&] { gso.updateState(nullptr, nullptr, nullptr); };
  step();  // new nodes: waits
  step();  // the closure 0 -> 2: optimised
  EXPECT_EQ(gso.optimisations(), 1u);
  step();
  EXPECT_EQ(gso.optimisations(), 1u);  // nothing changed
  graph.edges.erase(graph.edges.find({0, 2}));
  graph.insertEdge(1, 4, edgeAlongX(0.3, 1e4));  // one out, one in: the count of closures is the same
  step();
  EXPECT_EQ(gso.optimisations(), 2u);
  graph.edges.erase(graph.edges.find({1, 4}));
  step();
  EXPECT_EQ(gso.optimisations(), 3u);
}

TEST(CGaspPoseGraphGSO, TheHookRemovesEdgesBeforeTheNextOptimisation) {
  // Nodes 0.1 m apart along x. The closure 1 -> 4 is 0.5 m off and removed; the hook then takes
  // out 0 -> 5, which is 2 cm off: node 5 ends where the odometry puts it only when 0 -> 5 takes
  // no part in the optimisation after the removal.
  Graph3D graph = nodesAlongX(6);
  for (int i = 0; i < 5; ++i) graph.insertEdge(i, i + 1, edgeAlongX(0.1, 1e4));
  graph.insertEdge(1, 4, edgeAlongX(0.8, 1e4));
  graph.insertEdge(0, 5, edgeAlongX(0.52, 1e2));
  gasp::graphslam::CGaspPoseGraphGSO gso;
  gso.setGraphPtr(&graph);
  std::size_t calls = 0;
  gso.setAfterEdgeRemoval([&] {
    ++calls;
    EXPECT_EQ(graph.edges.count({1, 4}), 0u);
    graph.edges.erase(graph.edges.find({0, 5}));
    return std::size_t{1};
  });
  gso.optimizeNow();
  EXPECT_EQ(calls, 1u);
  EXPECT_EQ(gso.droppedEdges(), 1u);
  EXPECT_EQ(gso.optimisations(), 2u);
  EXPECT_EQ(graph.edgeCount(), 5u);
  EXPECT_NEAR(graph.nodes.at(5).x(), 0.5, 1e-6);
}

TEST(CGaspLoopClosureERD, TakesOutTheOtherVotesOfARelocalisationTheOptimiserCutDown) {
  // The relocalisation of the test above joins two pieces with two agreeing votes. When an
  // optimiser removes one, the other alone would be an unchecked join: the loop closer takes it
  // out of the graph as well, and says why.
  const std::string dir = gasp::test::scratchDir();
  const auto s = gasp::test::circleSequence(30, {12, 13, 14});
  GaspEngine e(writeFile(dir + "/g.ini", kEngineSections));
  for (std::size_t i = 0; i < s.depth.size(); ++i) e.step(scanOf(s, i));
  e.gso.optimizeNow();
  EXPECT_EQ(e.erd.syncWithGraph(), 0u);
  const auto accepted = [&] {
    std::size_t n = 0;
    for (const auto& a : e.erd.attempts()) n += a.accepted && a.relocalisation ? 1 : 0;
    return n;
  };
  const std::size_t votes = accepted(), inserted = e.erd.insertedEdges(), edges = e.graph().edgeCount();
  ASSERT_GE(votes, 2u);
  std::size_t cut = 0;
  while (!e.erd.attempts()[cut].accepted || !e.erd.attempts()[cut].relocalisation) ++cut;
  const auto& vote = e.erd.attempts()[cut];
  // The vote's edge is the last between its nodes (a vote between consecutive nodes follows the
  // node decider's break edge). The engine's graph stands in for an optimiser's here.
  auto& graph = const_cast<Graph3D&>(e.graph());
  graph.edges.erase(std::prev(graph.edges.equal_range({vote.from, vote.to}).second));
  // gasp-graphslam's end: optimise, forget, and optimise again without the partner.
  const std::size_t optimisations = e.gso.optimisations();
  gasp::graphslam::finishGraph(&e.gso, &e.erd);
  EXPECT_EQ(e.gso.optimisations(), optimisations + 2);
  const std::size_t taken_out = 1;  // its one partner (relocalisation_agreeing = 2)
  EXPECT_EQ(accepted(), votes - 1 - taken_out);
  EXPECT_EQ(e.erd.insertedEdges(), inserted - 1 - taken_out);
  EXPECT_EQ(e.graph().edgeCount(), edges - 1 - taken_out);
  EXPECT_EQ(e.erd.attempts()[cut].reason, "removed from the graph by the optimiser");
  std::size_t with_it = 0;
  for (const auto& a : e.erd.attempts())
    with_it += a.reason.find("a vote it joined two pieces with was removed") != std::string::npos ? 1 : 0;
  EXPECT_EQ(with_it, taken_out);
  EXPECT_EQ(e.erd.syncWithGraph(), 0u);
}

TEST(RawlogRun, GivesTheSelectedScansAndARecordPerNode) {
  // gasp-graphslam's run over a rawlog: scans 1, 3, 5, ... of a circle, ten of them.
  const std::string dir = gasp::test::scratchDir();
  const auto s = gasp::test::circleSequence(30);
  {
    gasp::RawlogWriter writer(dir + "/circle.rawlog");
    for (std::size_t i = 0; i < s.depth.size(); ++i) {
      gasp::RgbdFrame f;
      f.timestamp = s.timestamps[i];
      f.depth_m = s.depth[i];
      f.depth_intrinsics = s.K;
      f.T_robot_camera = mounting();
      writer.write(f);
    }
  }
  GaspEngine e(writeFile(dir + "/g.ini", kEngineSections));
  gasp::RawlogEntries entries(dir + "/circle.rawlog");
  gasp::graphslam::RawlogRunOptions options;
  options.selection.first = 1;
  options.selection.every = 2;
  options.selection.max_scans = 10;
  options.keep_depth = true;
  options.progress_every = 0;
  const auto run = gasp::graphslam::runOverRawlog(*e.engine, entries, "", &e.nrd, options);
  EXPECT_EQ(run.scans, 10u);
  EXPECT_EQ(run.seen_scans, 20u);  // the tenth used is scan 19
  EXPECT_EQ(run.steps, 10u);
  ASSERT_EQ(run.nodes.size(), e.graph().nodeCount());
  ASSERT_GE(run.nodes.size(), 2u);
  for (std::size_t i = 0; i < run.nodes.size(); ++i) {
    const std::size_t scan = 1 + 2 * e.nrd.nodeFrames()[i];  // odometry frame k is scan 1 + 2k
    EXPECT_DOUBLE_EQ(run.nodes[i].timestamp, s.timestamps[scan]) << i;
    EXPECT_TRUE(run.nodes[i].mounted);
    EXPECT_TRUE(run.nodes[i].T_robot_camera.isApprox(mounting(), 1e-9));
    ASSERT_TRUE(run.nodes[i].frame.has_value());
    EXPECT_LE(cv::norm(run.nodes[i].frame->depth_m, s.depth[scan], cv::NORM_INF), 0.0011) << i;  // as stored: mm
    EXPECT_TRUE(run.nodes[i].frame->rgb.empty());
  }
  gasp::graphslam::finishGraph(&e.gso, &e.erd);
  const gasp::Trajectory trajectory = gasp::graphslam::nodeTrajectory(e.graph(), run.nodes);
  ASSERT_EQ(trajectory.size(), run.nodes.size());
  EXPECT_TRUE(trajectory[0].T_world_camera.isApprox(mounting(), 1e-9));  // the root's robot frame is the world
  // The last node's camera, against the truth (the world being the root's robot frame).
  const std::size_t last = trajectory.size() - 1;
  const Isometry3 T_world_root = s.T_world_camera[1 + 2 * e.nrd.nodeFrames()[0]] * mounting().inverse();
  const Isometry3 err = (T_world_root.inverse() * s.T_world_camera[1 + 2 * e.nrd.nodeFrames()[last]]).inverse() *
                        trajectory[last].T_world_camera;
  EXPECT_LT(gasp::translationNorm(err), 0.03);
  EXPECT_LT(gasp::rotationAngle(err) * 180 / M_PI, 2.0);
  auto fewer = run.nodes;
  fewer.pop_back();
  EXPECT_THROW(gasp::graphslam::nodeTrajectory(e.graph(), fewer), gasp::Error);
}

TEST(GaspOptionsChecker, RegistersGaspsClassesBesideMrptsFor3DGraphs) {
  gasp::graphslam::GaspOptionsChecker checker;
  EXPECT_TRUE(checker.checkRegistrationDeciderExists("CGaspOdometryNRD", "node"));
  EXPECT_TRUE(checker.checkRegistrationDeciderExists("CGaspLoopClosureERD", "edge"));
  EXPECT_TRUE(checker.checkOptimizerExists("CGaspPoseGraphGSO"));
  EXPECT_TRUE(checker.checkRegistrationDeciderExists("CFixedIntervalsNRD", "node"));
  EXPECT_TRUE(checker.checkOptimizerExists("CLevMarqGSO"));
  EXPECT_FALSE(checker.checkRegistrationDeciderExists("CICPCriteriaNRD", "node"));  // 2D only
  EXPECT_FALSE(checker.checkOptimizerExists("CEmptyGSO"));  // MRPT maps it to CLevMarqGSO
  EXPECT_EQ(checker.optimizers_map.count("CEmptyGSO"), 0u);
  std::unique_ptr<mrpt::graphslam::deciders::CNodeRegistrationDecider<Graph3D>> nrd(
      checker.node_regs_map.at("CGaspOdometryNRD")());
  std::unique_ptr<mrpt::graphslam::deciders::CEdgeRegistrationDecider<Graph3D>> erd(
      checker.edge_regs_map.at("CGaspLoopClosureERD")());
  std::unique_ptr<mrpt::graphslam::optimizers::CGraphSlamOptimizer<Graph3D>> gso(
      checker.optimizers_map.at("CGaspPoseGraphGSO")());
  EXPECT_NE(dynamic_cast<gasp::graphslam::CGaspOdometryNRD*>(nrd.get()), nullptr);
  EXPECT_NE(dynamic_cast<gasp::graphslam::CGaspLoopClosureERD*>(erd.get()), nullptr);
  EXPECT_NE(dynamic_cast<gasp::graphslam::CGaspPoseGraphGSO*>(gso.get()), nullptr);
}

TEST(GraphSlamIni, MalformedLinesAndUnreadSectionsAreFound) {
  const std::string dir = gasp::test::scratchDir();
  auto c = gasp::graphslam::checkGraphSlamIni(writeFile(dir + "/ok.ini", "# comment\n; also\n\n[GeneralConfiguration]\n"
                                                                                "output_dir_fname = x\n[CGaspOdometryNRD]\n"
                                                                                "keyframe_distance_m=0.2\n"));
  EXPECT_TRUE(c.error.empty()) << c.error;
  EXPECT_TRUE(c.unknown_sections.empty());
  c = gasp::graphslam::checkGraphSlamIni(writeFile(dir + "/typo.ini", "[CGaspLoopClosureRD]\nenabled = 0\n[CGaspPoseGraphGSO]\n"
                                                                          "max_iterations 7\n"));
  EXPECT_NE(c.error.find("typo.ini:4: neither a [section] nor 'key = value'"), std::string::npos) << c.error;
  ASSERT_EQ(c.unknown_sections.size(), 1u);
  EXPECT_EQ(c.unknown_sections[0], "CGaspLoopClosureRD");
  c = gasp::graphslam::checkGraphSlamIni(writeFile(dir + "/garbage.ini", "this is not an ini file\n"));
  EXPECT_NE(c.error.find("garbage.ini:1"), std::string::npos) << c.error;
  c = gasp::graphslam::checkGraphSlamIni(writeFile(dir + "/section.ini", "[CGaspOdometryNRD\n"));
  EXPECT_NE(c.error.find("section.ini:1: a section needs [NAME]"), std::string::npos) << c.error;
  EXPECT_THROW(gasp::graphslam::checkGraphSlamIni(dir + "/missing.ini"), gasp::Error);
}

TEST(GraphSlamDeciders, ReadTheirIniSectionsStrictly) {
  const std::string dir = gasp::test::scratchDir();
  const std::string ini = writeFile(dir + "/ok.ini",
                                    "[CGaspOdometryNRD]\nkeyframe_distance_m = 0.2\nsensor_label = KINECT\n"
                                    "scene_change = 0\nscene_change_max_violation_ratio = 0.4\nscene_change_gate_m = 0.03\n"
                                    "scene_change_max_angular_accel_radps2 = 4\n"
                                    "[CGaspLoopClosureERD]\nsearch_radius_m = 0.8\nmax_candidates = 4\nenabled = 0\n"
                                    "[CGaspPoseGraphGSO]\nmax_iterations = 7\ndrop_chi2 = 0\n");
  gasp::graphslam::CGaspOdometryNRD nrd;
  gasp::graphslam::CGaspLoopClosureERD erd;
  gasp::graphslam::CGaspPoseGraphGSO gso;
  nrd.loadParams(ini);
  erd.loadParams(ini);
  gso.loadParams(ini);
  EXPECT_DOUBLE_EQ(nrd.params().keyframe_distance_m, 0.2);
  EXPECT_FALSE(nrd.params().scene_change.enabled);
  EXPECT_DOUBLE_EQ(nrd.params().scene_change.max_violation_ratio, 0.4);
  EXPECT_DOUBLE_EQ(nrd.params().scene_change.gate_m, 0.03);
  EXPECT_DOUBLE_EQ(nrd.params().scene_change.max_angular_accel_radps2, 4.0);
  EXPECT_DOUBLE_EQ(nrd.params().scene_change.gate_deg, gasp::SceneChangeParams{}.gate_deg);  // not in the file
  EXPECT_DOUBLE_EQ(erd.loopParams().search_radius_m, 0.8);
  EXPECT_EQ(erd.loopParams().max_candidates, 4u);
  EXPECT_FALSE(erd.loopParams().enabled);
  EXPECT_EQ(gso.settings().max_iterations, 7);
  EXPECT_DOUBLE_EQ(gso.dropChi2(), 0.0);

  EXPECT_THROW(nrd.loadParams(writeFile(dir + "/a.ini", "[CGaspOdometryNRD]\nkeyframe_distanse_m = 0.2\n")),
               std::exception);
  EXPECT_THROW(nrd.loadParams(writeFile(dir + "/b.ini", "[CGaspOdometryNRD]\nkeyframe_distance_m = -1\n")),
               std::exception);
  EXPECT_THROW(nrd.loadParams(writeFile(dir + "/g.ini", "[CGaspOdometryNRD]\nscene_change = 2\n")), std::exception);
  EXPECT_THROW(nrd.loadParams(writeFile(dir + "/h.ini", "[CGaspOdometryNRD]\nscene_change_max_occluded_ratio = 1.5\n")),
               std::exception);
  EXPECT_THROW(erd.loadParams(writeFile(dir + "/c.ini", "[CGaspLoopClosureERD]\nmax_candidates = -2\n")),
               std::exception);
  EXPECT_THROW(erd.loadParams(writeFile(dir + "/e.ini", "[CGaspLoopClosureERD]\nmin_keyframe_gap = 1\n")),
               std::exception);
  erd.loadParams(writeFile(dir + "/f.ini", "[CGaspLoopClosureERD]\nloop_min_inliers = 33\nmin_inliers = 9\n"));
  EXPECT_EQ(erd.loopParams().min_inliers, 33);           // the loop closer's
  EXPECT_EQ(erd.pairParams().hypothesise.pose.ransac.min_inliers, 9);  // RANSAC's
  EXPECT_THROW(gso.loadParams(writeFile(dir + "/d.ini", "[CGaspPoseGraphGSO]\nmax_iterations = many\n")),
               std::exception);
  EXPECT_THROW(gso.loadParams(dir + "/missing.ini"), std::exception);
  EXPECT_DOUBLE_EQ(nrd.params().keyframe_distance_m, 0.2);  // a failed load changes nothing
}

TEST(GraphTypes, BreakEdgesAndDepthScansAreTold) {
  mrpt::poses::CPose3DPDFGaussianInf e;
  e.cov_inv.setIdentity();
  e.cov_inv *= gasp::graphslam::kBreakInformation;
  EXPECT_TRUE(gasp::graphslam::isBreakEdge(e));
  e.cov_inv(0, 0) = 1.0;  // one direction constrained: not a break
  EXPECT_FALSE(gasp::graphslam::isBreakEdge(e));
  mrpt::poses::CPose3DPDFGaussianInf unknown;
  unknown.cov_inv.setIdentity();
  unknown.cov_inv(2, 3) = std::numeric_limits<double>::quiet_NaN();  // as MRPT's CFixedIntervalsNRD's first edge
  EXPECT_TRUE(gasp::graphslam::isBreakEdge(unknown));

  // For graph files: non-finite information becomes a break's; the mean and other edges stay.
  gasp::graphslam::Graph3D g;
  g.nodes[0] = mrpt::poses::CPose3D();
  g.nodes[1] = mrpt::poses::CPose3D(1, 0, 0, 0, 0, 0);
  g.nodes[2] = mrpt::poses::CPose3D(2, 0, 0, 0, 0, 0);
  unknown.mean = mrpt::poses::CPose3D(1, 0, 0, 0, 0, 0);
  g.insertEdge(0, 1, unknown);
  g.insertEdge(1, 2, e);
  EXPECT_EQ(gasp::graphslam::breakNonFiniteEdges(g), 1u);
  const auto& fixed = g.edges.find({0, 1})->second;
  EXPECT_TRUE(gasp::graphslam::isBreakEdge(fixed));
  EXPECT_DOUBLE_EQ(fixed.cov_inv(0, 0), gasp::graphslam::kBreakInformation);
  EXPECT_DOUBLE_EQ(fixed.cov_inv(2, 3), 0.0);
  EXPECT_DOUBLE_EQ(fixed.mean.x(), 1.0);
  EXPECT_DOUBLE_EQ(g.edges.find({1, 2})->second.cov_inv(0, 0), 1.0);
  EXPECT_EQ(gasp::graphslam::breakNonFiniteEdges(g), 0u);

  const auto s = gasp::test::circleSequence(2);
  auto scan = scanOf(s, 0);
  scan->sensorLabel = "KINECT";
  auto sf = std::make_shared<mrpt::obs::CSensoryFrame>();
  sf->insert(scan);
  EXPECT_EQ(gasp::graphslam::depthScanOf(sf, nullptr, ""), scan);
  EXPECT_EQ(gasp::graphslam::depthScanOf(sf, nullptr, "KINECT"), scan);
  EXPECT_EQ(gasp::graphslam::depthScanOf(sf, nullptr, "OTHER"), nullptr);
  EXPECT_EQ(gasp::graphslam::depthScanOf(nullptr, scan, ""), scan);
  EXPECT_EQ(gasp::graphslam::depthScanOf(nullptr, nullptr, ""), nullptr);
  // A LiDAR's sweep stored as a 3D scan of its points alone (gasp-tum2rawlog --points,
  // toPointsScan()) is no depth scan, before or after the camera's in the frame.
  auto points = std::make_shared<mrpt::obs::CObservation3DRangeScan>();
  points->sensorLabel = "LIDAR";
  points->hasRangeImage = false;
  points->resizePoints3DVectors(3);
  points->hasPoints3D = true;
  auto mixed = std::make_shared<mrpt::obs::CSensoryFrame>();
  mixed->insert(points);
  mixed->insert(scan);
  EXPECT_EQ(gasp::graphslam::depthScanOf(mixed, nullptr, ""), scan);
  EXPECT_EQ(gasp::graphslam::depthScanOf(nullptr, points, ""), nullptr);
  EXPECT_EQ(gasp::graphslam::depthScanOf(nullptr, points, "LIDAR"), nullptr);
}

TEST(ScanSelection, UsesFirstEveryAndMax) {
  const gasp::graphslam::ScanSelection all;
  for (std::size_t k = 0; k < 5; ++k) EXPECT_TRUE(all.uses(k));
  EXPECT_FALSE(all.done(1000));
  const gasp::graphslam::ScanSelection some{2, 3, 2};
  std::vector<std::size_t> used;
  for (std::size_t k = 0; k < 12; ++k)
    if (some.uses(k)) used.push_back(k);
  EXPECT_EQ(used, (std::vector<std::size_t>{2, 5, 8, 11}));
  EXPECT_FALSE(some.done(1));
  EXPECT_TRUE(some.done(2));
}

TEST(SkippedMotion, ComposesTheLeftOutStepsWithTheNextOne) {
  using mrpt::poses::CPose3D;
  const auto actionsOf = [](const CPose3D& move, double sigma, mrpt::Clock::time_point t) {
    auto actions = std::make_shared<mrpt::obs::CActionCollection>();
    mrpt::obs::CActionRobotMovement3D a;
    a.poseChange.mean = move;
    a.poseChange.cov.setIdentity();
    a.poseChange.cov *= sigma * sigma;
    a.timestamp = t;
    actions->insert(a);
    return actions;
  };
  const CPose3D m1(0.1, 0, 0, 0.3, 0, 0), m2(0.2, 0.05, 0, -0.1, 0.02, 0), m3(0, 0.1, 0.01, 0.2, 0, 0.05);
  const auto t3 = mrpt::Clock::fromDouble(3.0);
  gasp::graphslam::SkippedMotion held;
  EXPECT_TRUE(held.empty());
  const auto as_is = actionsOf(m1, 0.01, t3);
  EXPECT_EQ(held.prepend(as_is), as_is);  // nothing held: the step's own actions
  held.add(std::make_shared<mrpt::obs::CActionCollection>());  // no movement: nothing
  held.add(nullptr);
  EXPECT_TRUE(held.empty());
  held.add(actionsOf(m1, 0.01, mrpt::Clock::fromDouble(1.0)));
  held.add(actionsOf(m2, 0.01, mrpt::Clock::fromDouble(2.0)));
  EXPECT_FALSE(held.empty());
  const auto merged = held.prepend(actionsOf(m3, 0.01, t3));
  EXPECT_TRUE(held.empty());
  ASSERT_EQ(merged->size(), 1u);
  EXPECT_EQ(merged->get(0)->timestamp, t3);
  mrpt::poses::CPose3DPDFGaussian move;
  ASSERT_TRUE(merged->getFirstMovementEstimation(move));
  const CPose3D expected = m1 + m2 + m3;
  EXPECT_NEAR((move.mean.asVectorVal() - expected.asVectorVal()).norm(), 0.0, 1e-12);
  // Three steps' uncertainty: more than one step's along every axis.
  for (int i = 0; i < 6; ++i) EXPECT_GT(move.cov(i, i), 1.5 * 0.01 * 0.01) << i;
}
