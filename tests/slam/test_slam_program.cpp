// gasp-slam end to end: a simulated folder, its outputs (trajectory, graph, MRPT
// simple map, point map, CSVs), and the exit codes of bad input.
#include <gtest/gtest.h>

#include <mrpt/maps/CSimpleMap.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/obs/CObservationPointCloud.h>
#include <mrpt/obs/CObservationRotatingScan.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPose3DPDF.h>
#include <mrpt/poses/CPose3DPDFGaussian.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "gasp/core/tum_dataset.h"
#include "gasp/core/tum_trajectory.h"
#include "gasp/rawlog/observation_conversion.h"
#include "gasp/rawlog/range_scan.h"
#include "gasp/slam/point_map.h"
#include "depth_difference.h"
#include "gasp_test_data.h"
#include "program_run.h"
#include "two_session_job.h"

namespace {

using gasp::test::contains;
using gasp::test::countLinesStartingWith;
using gasp::test::medianAbsDifference;
using gasp::test::printedCount;
using gasp::test::runProgram;

/// A 30-frame simulated room at 5 Hz in DIR/sim (the occluder appears at frame 19). Each test
/// makes its own: ctest runs the tests of this file in parallel processes.
std::string simulatedFolder(const std::string& dir) {
  const std::string d = dir + "/sim";
  const auto run = runProgram("gasp-simulate", "--out " + d + " --frames 30 --rate 5");
  EXPECT_EQ(run.exit_code, 0) << run.output;
  return d;
}

}  // namespace

TEST(GaspSlamProgram, WritesTheTrajectoryGraphSimpleMapAndCloud) {
  const std::string out = gasp::test::scratchDir();
  const auto run = runProgram("gasp-slam", "--tum " + simulatedFolder(out) + " --max-frames 16 --out " + out +
                                               "/traj.txt --odometry-out " + out + "/odo.txt --graph " + out +
                                               "/g.graph --simplemap " + out + "/map.simplemap --cloud " + out +
                                               "/map.ply --loops-csv " + out + "/loops.csv --frames-csv " + out + "/f.csv --marginals-csv " +
                                               out + "/m.csv");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_TRUE(contains(run.output, "frames: 16\n")) << run.output;
  EXPECT_TRUE(contains(run.output, "tracked: 16\n")) << run.output;
  EXPECT_TRUE(contains(run.output, "graph_pieces: 1 ")) << run.output;
  const std::size_t keyframes = printedCount(run.output, "keyframes: ");
  const std::size_t loops = printedCount(run.output, "loop_closures: ");
  ASSERT_LT(keyframes, 17u) << run.output;
  ASSERT_LT(loops, 100u) << run.output;
  EXPECT_EQ(gasp::readTumTrajectory(out + "/traj.txt").size(), 16u);
  EXPECT_EQ(gasp::readTumTrajectory(out + "/odo.txt").size(), 16u);
  EXPECT_EQ(countLinesStartingWith(out + "/g.graph", "VERTEX3 "), 16u);
  EXPECT_EQ(countLinesStartingWith(out + "/g.graph", "EDGE3 "), 15u + loops);
  EXPECT_EQ(countLinesStartingWith(out + "/loops.csv", "from,to,relocalisation,accepted"), 1u);
  EXPECT_EQ(countLinesStartingWith(out + "/f.csv", "15,"), 1u);
  // The ATE against the folder's ground truth is below a centimetre.
  const auto pos = run.output.find("\nate_rmse_m: ");
  ASSERT_NE(pos, std::string::npos) << run.output;
  EXPECT_LT(std::stod(run.output.substr(pos + 13)), 0.01) << run.output;

  // The simple map: one scan per keyframe at the trajectory's pose (world = the first robot
  // frame: the camera's sensorPose applied).
  mrpt::maps::CSimpleMap map;
  ASSERT_TRUE(map.loadFromFile(out + "/map.simplemap"));
  ASSERT_EQ(map.size(), keyframes);
  const auto traj = gasp::readTumTrajectory(out + "/traj.txt");
  const auto [pose, sf] = map.get(0);
  ASSERT_TRUE(pose && sf);
  const auto scan = sf->getObservationByClass<mrpt::obs::CObservation3DRangeScan>();
  ASSERT_TRUE(scan);
  EXPECT_TRUE(scan->hasRangeImage);
  const gasp::Isometry3 T_world_robot = gasp::fromCPose3D(pose->getMeanVal());
  // Frame 0 is a keyframe at the origin of the world: the robot's pose is the identity.
  EXPECT_TRUE(T_world_robot.isApprox(gasp::Isometry3::Identity(), 1e-6));
  // The point map has points.
  EXPECT_GT(printedCount(run.output, "cloud: " + out + "/map.ply ("), 1000u) << run.output;

  // The poses' marginal covariances: zero at frame 0 (the gauge), centimetres further on,
  // in the map (MRPT's [x y z yaw pitch roll]), the CSV and the printout.
  EXPECT_TRUE(contains(run.output, "marginals: 16 frames (")) << run.output;
  EXPECT_TRUE(contains(run.output, "marginals_nees: median ")) << run.output;
  const auto gaussian = [&](std::size_t k) {
    return std::dynamic_pointer_cast<const mrpt::poses::CPose3DPDFGaussian>(std::get<0>(map.get(k)));
  };
  ASSERT_TRUE(gaussian(0));
  EXPECT_EQ(gaussian(0)->cov.norm(), 0.0);
  ASSERT_GE(keyframes, 2u);
  const auto last = gaussian(keyframes - 1);
  ASSERT_TRUE(last);
  const double sigma_x = std::sqrt(last->cov(0, 0)), sigma_yaw = std::sqrt(last->cov(3, 3));
  EXPECT_GT(sigma_x, 0.01);  // measured 3-6 cm per axis after 3 s at 5 Hz (the model error, slam.md)
  EXPECT_LT(sigma_x, 0.1);
  EXPECT_GT(sigma_yaw, 0.01);
  EXPECT_LT(sigma_yaw, 0.1);
  EXPECT_EQ(countLinesStartingWith(out + "/m.csv", "frame,timestamp,root,sigma_t_m,sigma_r_deg,c00,"), 1u);
  EXPECT_EQ(countLinesStartingWith(out + "/m.csv", "0,"), 1u);
  EXPECT_EQ(countLinesStartingWith(out + "/m.csv", "15,"), 1u);
}

TEST(GaspSlamProgram, ARawlogGivesTheFoldersPosesLoopClosuresAndMap) {
  // The folder's first 16 frames through gasp-tum2rawlog: the same depth, intrinsics and stamps,
  // so the same odometry, loop closures and optimised poses; the map's poses are robot poses,
  // the first one the world's origin.
  const std::string out = gasp::test::scratchDir();
  const std::string sim = simulatedFolder(out);
  auto run = runProgram("gasp-tum2rawlog", sim + " " + out + "/sim.rawlog --max-frames 16 --no-rgb");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const auto folder_run = runProgram("gasp-slam", "--tum " + sim + " --max-frames 16 --out " + out + "/tum.txt");
  ASSERT_EQ(folder_run.exit_code, 0) << folder_run.output;
  run = runProgram("gasp-slam", "--rawlog " + out + "/sim.rawlog --gt " + out + "/sim_groundtruth.txt --out " + out +
                                    "/rawlog.txt --simplemap " + out + "/map.simplemap --marginals-csv " + out + "/m.csv");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_TRUE(contains(run.output, "frames: 16\n")) << run.output;
  EXPECT_TRUE(contains(run.output, "graph_pieces: 1 ")) << run.output;
  EXPECT_TRUE(contains(run.output, "marginals: 16 frames (")) << run.output;
  EXPECT_TRUE(contains(run.output, "ate_rmse_m: ")) << run.output;
  const std::size_t loops = printedCount(run.output, "loop_closures: ");
  EXPECT_EQ(loops, printedCount(folder_run.output, "loop_closures: ")) << run.output << folder_run.output;
  const auto from_tum = gasp::readTumTrajectory(out + "/tum.txt");
  const auto from_rawlog = gasp::readTumTrajectory(out + "/rawlog.txt");
  ASSERT_EQ(from_tum.size(), 16u);
  ASSERT_EQ(from_rawlog.size(), 16u);
  for (std::size_t i = 0; i < 16; ++i) {
    EXPECT_NEAR(from_rawlog[i].timestamp, from_tum[i].timestamp, 1e-6);
    EXPECT_TRUE(from_rawlog[i].T_world_camera.isApprox(from_tum[i].T_world_camera, 1e-6)) << i;
  }
  mrpt::maps::CSimpleMap map;
  ASSERT_TRUE(map.loadFromFile(out + "/map.simplemap"));
  const std::size_t keyframes = printedCount(run.output, "keyframes: ");
  ASSERT_EQ(map.size(), keyframes);
  const auto [pose, sf] = map.get(0);
  ASSERT_TRUE(pose && sf);
  EXPECT_TRUE(gasp::fromCPose3D(pose->getMeanVal()).isApprox(gasp::Isometry3::Identity(), 1e-6));
  const auto scan = sf->getObservationByClass<mrpt::obs::CObservation3DRangeScan>();
  ASSERT_TRUE(scan);
  EXPECT_TRUE(scan->hasRangeImage);
  EXPECT_EQ(countLinesStartingWith(out + "/m.csv", "15,"), 1u);
}

TEST(GaspSlamProgram, WithTheDeskewTheMapHoldsTheDepthEachKeyframeWasRegisteredWith) {
  // --rolling-shutter deskews each frame (with the last step's velocity) before registering it;
  // a deskewed keyframe's scan in the map is that depth, not the recorded one (keyframe_map.h).
  // The first keyframe has no velocity yet: it keeps the recorded depth.
  const std::string out = gasp::test::scratchDir();
  const std::string folder = simulatedFolder(out);
  const auto run = runProgram("gasp-slam", "--tum " + folder + " --max-frames 12 --rolling-shutter 0.03 --out " + out +
                                               "/traj.txt --simplemap " + out + "/map.simplemap --frames-csv " + out +
                                               "/f.csv");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  // The keyframes, and which were deskewed, from the frames CSV
  // (index,timestamp,tracked,keyframe,reference,patches,inliers,deskewed,...).
  std::ifstream csv(out + "/f.csv");
  std::string line;
  std::getline(csv, line);
  ASSERT_EQ(line.rfind("index,timestamp,tracked,keyframe,reference,patches,inliers,deskewed,", 0), 0u) << line;
  std::vector<std::pair<std::size_t, bool>> keyframes;  // (frame, deskewed)
  while (std::getline(csv, line)) {
    std::vector<std::string> cells;
    std::stringstream ss(line);
    for (std::string cell; std::getline(ss, cell, ',');) cells.push_back(cell);
    ASSERT_GE(cells.size(), 8u) << line;
    if (cells[3] == "1") keyframes.emplace_back(std::stoul(cells[0]), cells[7] == "1");
  }
  ASSERT_GE(keyframes.size(), 3u);
  ASSERT_FALSE(keyframes.front().second);  // no velocity before the first frame

  mrpt::maps::CSimpleMap map;
  ASSERT_TRUE(map.loadFromFile(out + "/map.simplemap"));
  ASSERT_EQ(map.size(), keyframes.size());
  const gasp::TumDataset data = gasp::TumDataset::open(folder);
  int deskewed = 0;
  for (std::size_t k = 0; k < keyframes.size(); ++k) {
    const auto scan = std::get<1>(map.get(k))->getObservationByClass<mrpt::obs::CObservation3DRangeScan>();
    ASSERT_TRUE(scan);
    const cv::Mat recorded = data.loadDepthRaw(keyframes[k].first);
    ASSERT_EQ(scan->rangeImage.cols(), recorded.cols);
    ASSERT_EQ(scan->rangeImage.rows(), recorded.rows);
    int differing = 0;
    for (int r = 0; r < recorded.rows; ++r)
      for (int c = 0; c < recorded.cols; ++c) differing += scan->rangeImage(r, c) != recorded.at<std::uint16_t>(r, c);
    if (keyframes[k].second) {
      ++deskewed;
      EXPECT_GT(differing, recorded.rows * recorded.cols / 100) << "keyframe " << keyframes[k].first;
      EXPECT_FALSE(scan->hasIntensityImage);
      // It is this frame's depth, moved by the deskew, not another frame's: it differs from the
      // recorded image less than the frame before's recording does (measured 4-9 mm against 8-22 cm).
      const double own = medianAbsDifference(scan->rangeImage, recorded);
      const double previous = medianAbsDifference(scan->rangeImage, data.loadDepthRaw(keyframes[k].first - 1));
      EXPECT_GE(own, 0.0);
      EXPECT_LT(own, 0.5 * previous) << "keyframe " << keyframes[k].first << ": median |difference| " << own
                                     << " units to its recording, " << previous << " to the frame before's";
    } else {
      EXPECT_EQ(differing, 0) << "keyframe " << keyframes[k].first;
    }
  }
  EXPECT_GE(deskewed, 2);
}

TEST(GaspSlamProgram, SessionsOfAFolderAndARawlogThatShareFramesAreJoinedInOneWorld) {
  // Frames 0-9 of the folder, then frames 6-15 of the same scene as a rawlog: two sessions with
  // no known relation, which see frames 6-9 both. Joined, each session's trajectory is in the
  // first one's world, so the frames they share have the same pose in both files.
  const std::string out = gasp::test::scratchDir();
  const std::string sim = simulatedFolder(out);
  auto run = runProgram("gasp-tum2rawlog", sim + " " + out + "/sim.rawlog --max-frames 16 --no-rgb");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  run = runProgram("gasp-slam", "--session " + sim + "@0-9 --session " + out + "/sim.rawlog@6-15 --out " + out +
                                    "/traj.txt --odometry-out " + out + "/odo.txt --graph " + out + "/g.graph --sessions-report " +
                                    out + "/sessions.yaml");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_TRUE(contains(run.output, "sessions: 2 in 1 map\n")) << run.output;
  EXPECT_TRUE(contains(run.output, "map 1: sessions 1, 2 joined")) << run.output;
  const auto first = gasp::readTumTrajectory(out + "/traj.session1.txt");
  const auto second = gasp::readTumTrajectory(out + "/traj.session2.txt");
  ASSERT_EQ(first.size(), 10u);
  ASSERT_EQ(second.size(), 10u);
  EXPECT_EQ(gasp::readTumTrajectory(out + "/odo.session2.txt").size(), 10u);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_NEAR(first[6 + i].timestamp, second[i].timestamp, 1e-6);
    const gasp::Isometry3 e = first[6 + i].T_world_camera.inverse() * second[i].T_world_camera;
    EXPECT_LT(gasp::translationNorm(e), 0.01) << "frame " << 6 + i;
    EXPECT_LT(gasp::rotationAngle(e) * 180 / M_PI, 1.0) << "frame " << 6 + i;
  }
  std::ifstream yaml(out + "/sessions.yaml");
  std::stringstream report;
  report << yaml.rdbuf();
  EXPECT_TRUE(contains(report.str(), "  - session: 2\n")) << report.str();
  EXPECT_TRUE(contains(report.str(), "    map: 1\n    trajectory: ")) << report.str();
  EXPECT_TRUE(contains(report.str(), "maps:\n  - sessions: [1, 2]\n")) << report.str();
  EXPECT_EQ(countLinesStartingWith(out + "/g.graph", "VERTEX"), 20u);
}

TEST(GaspSlamProgram, ASessionThatGivesNoFrameIsReportedAndTheOthersAreStillJoined) {
  // The middle session asks for frames past the rawlog's end: no frame, an error said, exit 1 at
  // the end; the first and the last (which share frames 3-5) are joined all the same.
  const std::string out = gasp::test::scratchDir();
  const std::string sim = simulatedFolder(out);
  auto run = runProgram("gasp-tum2rawlog", sim + " " + out + "/sim.rawlog --max-frames 8 --no-rgb");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  run = runProgram("gasp-slam", "--session " + sim + "@0-5 --session " + out + "/sim.rawlog@50-60 --session " + sim +
                                    "@3-8 --out " + out + "/traj.txt --sessions-report " + out + "/r.yaml");
  EXPECT_EQ(run.exit_code, 1) << run.output;  // partial: a session ended with an error
  EXPECT_TRUE(contains(run.output, "sessions: 3 in 2 maps\n")) << run.output;
  EXPECT_TRUE(contains(run.output, "@50-60): no frame, 0 of 0 tracked (PARTIAL")) << run.output;
  EXPECT_TRUE(contains(run.output, "map 1: sessions 1, 3 joined")) << run.output;
  EXPECT_EQ(gasp::readTumTrajectory(out + "/traj.session2.txt").size(), 0u);
  EXPECT_EQ(gasp::readTumTrajectory(out + "/traj.session3.txt").size(), 6u);
}

TEST(GaspSlamProgram, SessionsOfDifferentScenesStayApartAndTheReportSaysSo) {
  const std::string out = gasp::test::scratchDir();
  const std::string sim = simulatedFolder(out);
  auto run = runProgram("gasp-simulate", "--scene repeated --out " + out + "/repeated --frames 8 --rate 5");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  run = runProgram("gasp-slam", "--session " + sim + "@0-5 --session " + out + "/repeated --out " + out + "/traj.txt");
  EXPECT_EQ(run.exit_code, 3) << run.output;  // written, the graph in pieces
  EXPECT_TRUE(contains(run.output, "sessions: 2 in 2 maps\n")) << run.output;
  EXPECT_TRUE(contains(run.output, "map 2: session 2 alone: no constraint joins it to another")) << run.output;
  EXPECT_EQ(gasp::readTumTrajectory(out + "/traj.session1.txt").size(), 6u);
  EXPECT_EQ(gasp::readTumTrajectory(out + "/traj.session2.txt").size(), 8u);
  // Each session aligned alone is right; no alignment over sessions in different maps.
  EXPECT_TRUE(contains(run.output, "session 2: ate_rmse_m: ")) << run.output;
  EXPECT_FALSE(contains(run.output, "in its map's frame")) << run.output;
}

TEST(GaspSlamProgram, BadInputExitsWith1OrAUsageCode) {
  const std::string out = gasp::test::scratchDir();
  auto run = runProgram("gasp-slam", "--tum " + out + "/nothing --out " + out + "/t.txt");
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_TRUE(contains(run.output, "error: ") && contains(run.output, "nothing")) << run.output;
  run = runProgram("gasp-slam", "--out " + out + "/t.txt");
  EXPECT_EQ(run.exit_code, 2) << run.output;
  run = runProgram("gasp-slam", "--tum " + out + " --rawlog x.rawlog --out " + out + "/t.txt");
  EXPECT_EQ(run.exit_code, 2) << run.output;
  const std::string sim = simulatedFolder(out);
  run = runProgram("gasp-slam", "--tum " + sim + " --voxel 0 --cloud " + out + "/c.ply --out " + out + "/t.txt");
  EXPECT_EQ(run.exit_code, 2) << run.output;  // an option value out of its range: a usage error
  EXPECT_TRUE(contains(run.output, "--voxel: must be between 0.001 and 10")) << run.output;
  std::ofstream(out + "/radius.yaml") << "loop_closure:\n  search_radius_m: -1\n";
  run = runProgram("gasp-slam", "--tum " + sim + " --params " + out + "/radius.yaml --out " + out + "/t.txt");
  EXPECT_EQ(run.exit_code, 1) << run.output;  // a bad params file: bad input, named before the run
  EXPECT_TRUE(contains(run.output, "(loop_closure.search_radius_m on line 2)")) << run.output;
  run = runProgram("gasp-slam", "--tum " + sim + " --max-frames 3 --simplemap /nonexistent-dir/m.simplemap --out " + out +
                                    "/t.txt");
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_TRUE(contains(run.output, "m.simplemap")) << run.output;
  // A rawlog that is not one.
  std::ofstream(out + "/garbage.rawlog") << "not a rawlog";
  run = runProgram("gasp-slam", "--rawlog " + out + "/garbage.rawlog --out " + out + "/t.txt");
  EXPECT_EQ(run.exit_code, 1) << run.output;
  // Sessions: a range backwards, a missing input (named before any session runs), --tum besides.
  run = runProgram("gasp-slam", "--session " + sim + "@5-2 --out " + out + "/t.txt");
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_TRUE(contains(run.output, "@5-2: the last frame comes before the first")) << run.output;
  run = runProgram("gasp-slam", "--session " + sim + " --session " + out + "/missing.rawlog --out " + out + "/t.txt");
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_TRUE(contains(run.output, "missing.rawlog")) << run.output;
  EXPECT_FALSE(contains(run.output, "frames: ")) << run.output;
  run = runProgram("gasp-slam", "--session " + sim + " --tum " + sim + " --out " + out + "/t.txt");
  EXPECT_EQ(run.exit_code, 2) << run.output;
}

TEST(GaspSlamProgram, TheOccluderFrameLeavesTheGraphInPiecesOrRejoinsItAndSaysSo) {
  // All 30 frames: the occluder pops in at frame 19. With --no-scene-change the odometry cannot
  // track it; the frames after it are registered to it, a new piece. The program exits 3 and says
  // why.
  const std::string out = gasp::test::scratchDir();
  const std::string sim = simulatedFolder(out);
  auto run = runProgram("gasp-slam", "--tum " + sim + " --no-scene-change --out " + out + "/t.txt --loops-csv " + out +
                                         "/loops.csv");
  EXPECT_EQ(run.exit_code, 3) << run.output;
  EXPECT_TRUE(contains(run.output, "not_tracked: 1 frames")) << run.output;
  EXPECT_TRUE(contains(run.output, "(odometry alone: 2)")) << run.output;
  EXPECT_EQ(gasp::readTumTrajectory(out + "/t.txt").size(), 30u);
  // By default the frame is taken through the scene change: every frame tracked, one piece.
  run = runProgram("gasp-slam", "--tum " + sim + " --out " + out + "/t2.txt");
  EXPECT_EQ(run.exit_code, 0) << run.output;
  EXPECT_TRUE(contains(run.output, "tracked: 30\n")) << run.output;
  EXPECT_TRUE(contains(run.output, "(odometry alone: 1)")) << run.output;
}

// A map of LiDAR sweeps (issue 49): the simple map holds each keyframe's sweep as it was read (a
// rotating scan, or a point cloud), and the cloud is the sweeps' returns at the optimised poses.
// Scored against the same keyframes' returns at their true poses (world = the first sweep).
TEST(GaspSlamProgram, MapsOfLidarSweepsHoldTheSweepsAsReadAndTheirReturnsWhereTheTruthPutsThem) {
  const std::string out = gasp::test::scratchDir();
  for (const bool clouds : {false, true}) {
    const std::string d = out + (clouds ? "/clouds" : "/scans");
    const auto sim = runProgram("gasp-simulate", std::string("--sensor lidar16 --frames 60 --rate 10") +
                                                     (clouds ? " --point-clouds" : "") + " --out " + d);
    ASSERT_EQ(sim.exit_code, 0) << sim.output;
    const auto run = runProgram("gasp-slam", "--rawlog " + d + "/lidar.rawlog --max-frames 20 --out " + d + "/t.txt --simplemap " + d +
                                                 "/map.simplemap --cloud " + d + "/map.ply --voxel 0.05 --cloud-max-depth 20");
    ASSERT_EQ(run.exit_code, 0) << run.output;
    mrpt::maps::CSimpleMap map;
    ASSERT_TRUE(map.loadFromFile(d + "/map.simplemap"));
    EXPECT_EQ(map.size(), printedCount(run.output, "simplemap: " + d + "/map.simplemap (")) << run.output;
    ASSERT_GE(map.size(), 2u);
    const gasp::Trajectory truth = gasp::readTumTrajectory(d + "/lidar_groundtruth.txt");
    ASSERT_FALSE(truth.empty());
    const gasp::Isometry3 T_first_world = truth.front().T_world_camera.inverse();
    gasp::VoxelPointMap at_truth(0.05, 20.0);
    for (const auto& [pose, frame] : map) {
      ASSERT_TRUE(pose && frame && frame->size() == 1u);
      const auto obs = frame->getObservationByIndex(0);
      if (clouds)
        EXPECT_TRUE(std::dynamic_pointer_cast<mrpt::obs::CObservationPointCloud>(obs)) << obs->GetRuntimeClass()->className;
      else
        EXPECT_TRUE(std::dynamic_pointer_cast<mrpt::obs::CObservationRotatingScan>(obs)) << obs->GetRuntimeClass()->className;
      const gasp::RangeScan scan = gasp::rangeScanFrom(*obs);
      const auto k = std::find_if(truth.begin(), truth.end(),
                                  [&](const gasp::StampedPose& t) { return std::abs(t.timestamp - scan.timestamp) < 1e-4; });
      ASSERT_NE(k, truth.end()) << scan.timestamp;
      // The simple map's robot pose, with the sweep's mounting (the simulator's: none), is the
      // LiDAR's: within a few centimetres of the truth.
      const gasp::Isometry3 T_world_lidar = gasp::fromCPose3D(pose->getMeanVal()) * scan.T_robot_sensor;
      const gasp::Isometry3 error = (T_first_world * k->T_world_camera).inverse() * T_world_lidar;
      EXPECT_LT(error.translation().norm(), 0.05) << scan.timestamp;
      EXPECT_LT(Eigen::AngleAxisd(error.linear()).angle(), 1.0 * M_PI / 180.0) << scan.timestamp;
      at_truth.insert(scan, T_first_world * k->T_world_camera);
    }
    // The map's cloud against the truth's: each point's nearest truth point.
    std::ifstream ply(d + "/map.ply");
    std::string line;
    std::size_t vertices = 0;
    while (std::getline(ply, line) && line != "end_header")
      if (line.rfind("element vertex ", 0) == 0) vertices = std::stoul(line.substr(15));
    const std::vector<Eigen::Vector3f> reference = at_truth.points();
    ASSERT_GT(vertices, 1000u);
    ASSERT_GT(reference.size(), 1000u);
    std::vector<double> nearest;
    for (std::size_t i = 0; i < vertices && std::getline(ply, line); i += 1) {
      if (i % 10 != 0) continue;  // every tenth point
      std::istringstream xyz(line);
      Eigen::Vector3f p;
      xyz >> p.x() >> p.y() >> p.z();
      double best = 1e9;
      for (const Eigen::Vector3f& q : reference) best = std::min(best, static_cast<double>((p - q).norm()));
      nearest.push_back(best);
    }
    std::sort(nearest.begin(), nearest.end());
    const double median = nearest[nearest.size() / 2], p90 = nearest[nearest.size() * 9 / 10];
    std::printf("%s: %zu keyframes, %zu points; to the truth's cloud: median %.3f m, 90 %% %.3f m\n",
                clouds ? "point clouds" : "rotating scans", map.size(), vertices, median, p90);
    EXPECT_LT(median, 0.02);  // 5 cm voxels of the same returns: about 1 cm apart at the truth
    EXPECT_LT(p90, 0.05);
  }
}

TEST(GaspSlamProgram, AJobKilledMidRunResumesFromItsCheckpointToTheSameGraph) {
  // Two sessions of the simulated room that share frames 20-24, the searches in place: killed
  // (SIGKILL) once two registrations are journaled, then started again with --resume, the job
  // writes the uninterrupted job's trajectories and graph byte for byte, registering only what
  // the journal did not hold.
  const std::string out = gasp::test::scratchDir();
  const gasp::test::TwoSessionJob two = gasp::test::twoSessionJob(out);
  const auto job = [&](const std::string& name) { return two.args(name) + " --checkpoint " + out + "/" + name + ".journal"; };
  const auto whole = runProgram("gasp-slam", job("whole"));
  ASSERT_TRUE(whole.exit_code == 0 || whole.exit_code == 3) << whole.output;
  const std::size_t registrations = countLinesStartingWith(out + "/whole.journal", "R\t");
  ASSERT_GE(registrations, 4u) << whole.output;
  EXPECT_TRUE(contains(whole.output, "registrations made, 0 answered from it)")) << whole.output;

  // The same job, killed.
  const std::string journal = out + "/cut.journal";
  const auto killed = gasp::test::runCommand(
      "bash -c '\"" + std::string(GASP_BIN_DIR) + "/gasp-slam\" " + job("cut") + " > " + out + "/cut.log 2>&1 & pid=$!; " +
      "for i in $(seq 1 2400); do n=$(grep -c \"^R\" " + journal + " 2>/dev/null); " +
      "[ \"${n:-0}\" -ge 2 ] && break; sleep 0.05; done; kill -9 $pid && echo killed; wait $pid; " +
      "echo records=$(grep -c \"^R\" " + journal + ")'");
  ASSERT_TRUE(contains(killed.output, "killed\n")) << killed.output;
  const std::size_t kept = printedCount(killed.output, "records=");
  ASSERT_GE(kept, 2u) << killed.output;
  ASSERT_LT(kept, registrations) << killed.output;

  const auto resumed = runProgram("gasp-slam", job("cut") + " --resume");
  EXPECT_EQ(resumed.exit_code, whole.exit_code) << resumed.output;
  EXPECT_TRUE(contains(resumed.output, "checkpoint: " + std::to_string(kept) + " registrations from")) << resumed.output;
  EXPECT_TRUE(contains(resumed.output, std::to_string(registrations - kept) + " registrations made, " +
                                           std::to_string(kept) + " answered from it)"))
      << resumed.output;
  for (const std::string file : {".session1.txt", ".session2.txt", ".graph"}) {
    const std::string a = gasp::test::fileText(out + "/whole" + file);
    EXPECT_FALSE(a.empty()) << file;
    EXPECT_EQ(a, gasp::test::fileText(out + "/cut" + file)) << file;
  }
  EXPECT_EQ(countLinesStartingWith(journal, "R\t"), registrations);

  gasp::test::ProgramRun other{0, ""};
  // A journal there already, without --resume; the journal an input or another output.
  other = runProgram("gasp-slam", job("cut"));
  EXPECT_EQ(other.exit_code, 1) << other.output;
  EXPECT_TRUE(contains(other.output, "holds a registration journal: add --resume")) << other.output;
  other = runProgram("gasp-slam", two.args("x") + " --checkpoint " + out + "/room/depth.txt");
  EXPECT_EQ(other.exit_code, 1) << other.output;
  EXPECT_TRUE(contains(other.output, "is the input")) << other.output;
  other = runProgram("gasp-slam", two.args("x") + " --checkpoint " + out + "/x.graph");
  EXPECT_EQ(other.exit_code, 1) << other.output;
  EXPECT_TRUE(contains(other.output, "is also the output of --graph")) << other.output;
  EXPECT_EQ(countLinesStartingWith(journal, "R\t"), registrations);  // untouched

  // Another job's journal (other frames), --resume without --checkpoint, a journal that is not one.
  other = runProgram("gasp-slam", "--session " + out + "/room@0-23 --session " + out + "/room@20-44 --params " + out +
                                           "/inplace.yaml --out " + out + "/o.txt --checkpoint " + journal + " --resume");
  EXPECT_EQ(other.exit_code, 1) << other.output;
  EXPECT_TRUE(contains(other.output, "is another job's")) << other.output;
  other = runProgram("gasp-slam", "--tum " + out + "/room --out " + out + "/o.txt --resume");
  EXPECT_EQ(other.exit_code, 2) << other.output;
  std::ofstream(out + "/notes.txt") << "not a journal\n";
  other = runProgram("gasp-slam", "--tum " + out + "/room --out " + out + "/o.txt --checkpoint " + out +
                                      "/notes.txt --resume");
  EXPECT_EQ(other.exit_code, 1) << other.output;
  EXPECT_TRUE(contains(other.output, "is not a GASP registration journal")) << other.output;
}
