// gasp-odometry end to end: a simulated folder, its outputs, and the exit codes of bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <opencv2/imgcodecs.hpp>

#include "gasp/core/tum_dataset.h"
#include "gasp_test_data.h"
#include "program_run.h"

namespace {

using gasp::test::contains;
using gasp::test::countLinesStartingWith;
using gasp::test::runProgram;

/// A 30-frame simulated room at 5 Hz (up to 1 m/s and 2 rad/s) in DIR/sim. Each test makes its
/// own: ctest runs the tests of this file in parallel processes.
std::string simulatedFolder(const std::string& dir) {
  const std::string d = dir + "/sim";
  const auto run = runProgram("gasp-simulate", "--out " + d + " --frames 30 --rate 5");
  EXPECT_EQ(run.exit_code, 0) << run.output;
  return d;
}

/// The line of frame `index` in a --frames-csv file ("" when there is none).
std::string frameLine(const std::string& csv, int index) {
  std::ifstream in(csv);
  const std::string head = std::to_string(index) + ",";
  for (std::string line; std::getline(in, line);)
    if (line.rfind(head, 0) == 0) return line;
  return "";
}

/// Cell `k` of a CSV line whose cells before the last hold no comma.
std::string csvCell(const std::string& line, int k) {
  std::stringstream fields(line);
  std::string cell;
  for (int i = 0; i <= k; ++i)
    if (!std::getline(fields, cell, ',')) return "";
  return cell;
}

}  // namespace

TEST(GaspOdometryProgram, WritesTheTrajectoryGraphAndFramesAndScoresThem) {
  // Frames 0-9, before the occluder appears.
  const std::string out = gasp::test::scratchDir();
  const auto run = runProgram("gasp-odometry", "--tum " + simulatedFolder(out) + " --max-frames 10 --out " + out +
                                                   "/traj.txt --graph " + out + "/odo.graph --frames-csv " + out +
                                                   "/frames.csv");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_TRUE(contains(run.output, "frames: 10\n")) << run.output;
  EXPECT_TRUE(contains(run.output, "tracked: 10\n")) << run.output;
  EXPECT_TRUE(contains(run.output, "graph_components: 1\n")) << run.output;
  EXPECT_TRUE(contains(run.output, "graph: " + out + "/odo.graph (10 nodes, 9 edges)")) << run.output;
  EXPECT_EQ(gasp::readTumTrajectory(out + "/traj.txt").size(), 10u);
  EXPECT_EQ(countLinesStartingWith(out + "/odo.graph", "VERTEX3 "), 10u);
  EXPECT_EQ(countLinesStartingWith(out + "/odo.graph", "EDGE3 "), 9u);
  EXPECT_EQ(countLinesStartingWith(out + "/frames.csv", "index,timestamp,tracked"), 1u);
  EXPECT_EQ(countLinesStartingWith(out + "/frames.csv", "9,"), 1u);
  // The ATE it prints (the folder's groundtruth.txt) is below a centimetre.
  const auto pos = run.output.find("ate_rmse_m: ");
  ASSERT_NE(pos, std::string::npos) << run.output;
  EXPECT_LT(std::stod(run.output.substr(pos + 12)), 0.01) << run.output;
}

TEST(GaspOdometryProgram, SegmentingAheadGivesTheSameTrajectoryAsSequential) {
  const std::string out = gasp::test::scratchDir();
  const std::string sim = simulatedFolder(out);
  for (const std::string mode : {"", " --sequential"}) {
    const auto run = runProgram("gasp-odometry", "--tum " + sim + " --max-frames 10 --out " + out + "/traj" +
                                                     (mode.empty() ? "" : "_seq") + ".txt" + mode);
    ASSERT_EQ(run.exit_code, 0) << run.output;
  }
  std::ifstream a(out + "/traj.txt"), b(out + "/traj_seq.txt");
  std::stringstream ta, tb;
  ta << a.rdbuf();
  tb << b.rdbuf();
  EXPECT_FALSE(ta.str().empty());
  EXPECT_EQ(ta.str(), tb.str());
}

TEST(GaspOdometryProgram, AFrameItCannotTrackExitsWith3AndSaysWhy) {
  // The occluder pops into the scene at frame 19 of 30: the visibility check refuses that frame's
  // pose (a static world is assumed). With --no-scene-change the frame is then predicted.
  const std::string out = gasp::test::scratchDir();
  const auto run = runProgram("gasp-odometry", "--tum " + simulatedFolder(out) + " --no-scene-change --out " + out +
                                                   "/traj.txt --frames-csv " + out + "/f.csv");
  EXPECT_EQ(run.exit_code, 3) << run.output;
  EXPECT_TRUE(contains(run.output, "tracked: 29\n")) << run.output;
  EXPECT_TRUE(contains(run.output, "graph_components: 2\n")) << run.output;
  EXPECT_TRUE(contains(run.output, "scene_changes: 0\n")) << run.output;
  EXPECT_TRUE(contains(run.output, "not_tracked: 1 frames")) << run.output;
  EXPECT_EQ(gasp::readTumTrajectory(out + "/traj.txt").size(), 30u);  // the lost frame's pose is predicted
  const std::string frame19 = frameLine(out + "/f.csv", 19);
  EXPECT_EQ(frame19.rfind("19,", 0), 0u) << frame19;
  EXPECT_EQ(csvCell(frame19, 2), "0") << frame19;   // tracked
  EXPECT_EQ(csvCell(frame19, 10), "0") << frame19;  // scene_change
  EXPECT_TRUE(contains(frame19, "visibility check")) << frame19;
  EXPECT_FALSE(contains(frame19, "scene change:")) << frame19;
}

TEST(GaspOdometryProgram, TracksThroughASceneChangeByDefault) {
  // The same folder without the flag: frame 19 is taken through the scene change (the pose agrees
  // with the constant-velocity prediction), every frame is tracked and the graph is in one piece.
  const std::string out = gasp::test::scratchDir();
  const auto run = runProgram("gasp-odometry", "--tum " + simulatedFolder(out) + " --out " + out +
                                                   "/traj.txt --frames-csv " + out + "/f.csv");
  EXPECT_EQ(run.exit_code, 0) << run.output;
  EXPECT_TRUE(contains(run.output, "tracked: 30\n")) << run.output;
  EXPECT_TRUE(contains(run.output, "graph_components: 1\n")) << run.output;
  EXPECT_TRUE(contains(run.output, "scene_changes: 1 (frames 19)\n")) << run.output;
  std::ifstream in(out + "/f.csv");
  std::string header;
  std::getline(in, header);
  EXPECT_EQ(header, "index,timestamp,tracked,keyframe,reference,patches,inliers,deskewed,segmentation_ms,"
                    "registration_ms,scene_change,partial,tracking_path,reason");
  for (int i = 0; i < 30; ++i) {
    const std::string line = frameLine(out + "/f.csv", i);
    EXPECT_EQ(csvCell(line, 2), "1") << line;
    EXPECT_EQ(csvCell(line, 10), i == 19 ? "1" : "0") << line;
  }
  const std::string frame19 = frameLine(out + "/f.csv", 19);
  EXPECT_EQ(csvCell(frame19, 3), "1") << frame19;   // the new keyframe
  EXPECT_EQ(csvCell(frame19, 4), "18") << frame19;  // registered to the previous frame
  EXPECT_TRUE(contains(frame19, "scene change: against the previous frame 18: taken")) << frame19;
}

TEST(GaspOdometryProgram, ARawlogGivesTheFoldersPosesAndRobotFrameGraph) {
  // The folder's frames 1, 3, 5, 7 (--first 1 --every 2 --max-frames 4) through gasp-tum2rawlog:
  // the same depth, intrinsics and stamps, so the same poses as from the folder.
  const std::string out = gasp::test::scratchDir();
  const std::string sim = simulatedFolder(out);
  auto run = runProgram("gasp-tum2rawlog", sim + " " + out + "/sim.rawlog --max-frames 10 --no-rgb");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const std::string selection = " --first 1 --every 2 --max-frames 4";
  run = runProgram("gasp-odometry", "--tum " + sim + selection + " --out " + out + "/tum.txt");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_TRUE(contains(run.output, "frames: 4\n")) << run.output;
  run = runProgram("gasp-odometry", "--rawlog " + out + "/sim.rawlog --gt " + out + "/sim_groundtruth.txt" + selection +
                                        " --out " + out + "/rawlog.txt --graph " + out + "/robot.graph");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_TRUE(contains(run.output, "tracked: 4\n") && contains(run.output, "ate_rmse_m: ")) << run.output;
  EXPECT_TRUE(contains(run.output, "(4 nodes, 3 edges)")) << run.output;
  const auto from_tum = gasp::readTumTrajectory(out + "/tum.txt");
  const auto from_rawlog = gasp::readTumTrajectory(out + "/rawlog.txt");
  const auto folder = gasp::TumDataset::open(sim);
  ASSERT_EQ(from_tum.size(), 4u);
  ASSERT_EQ(from_rawlog.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_NEAR(from_tum[i].timestamp, folder.frame(1 + 2 * i).timestamp, 1e-6);
    EXPECT_NEAR(from_rawlog[i].timestamp, from_tum[i].timestamp, 1e-6);
    EXPECT_TRUE(from_rawlog[i].T_world_camera.isApprox(from_tum[i].T_world_camera, 1e-6)) << i;
  }
  // The graph's nodes are robot frames (gasp-tum2rawlog's sensorPose is a rotation): node 0 is
  // not the camera's identity pose written in the trajectory.
  std::ifstream graph(out + "/robot.graph");
  std::string first_vertex;
  for (std::string line; std::getline(graph, line);)
    if (line.rfind("VERTEX3 0 ", 0) == 0) first_vertex = line;
  std::stringstream v(first_vertex);
  std::string key;
  int id = -1;
  double x, y, z, roll, pitch, yaw;
  ASSERT_TRUE(v >> key >> id >> x >> y >> z >> roll >> pitch >> yaw) << first_vertex;
  EXPECT_GT(std::abs(roll) + std::abs(pitch) + std::abs(yaw), 1.0) << first_vertex;
}

TEST(GaspOdometryProgram, AFolderOfAnotherCameraTakesItsIntrinsicsOrSaysWhatItAssumed) {
  // fr1_desk9 under a name that names no TUM camera, without intrinsics.txt: the ROS default is
  // assumed with a warning; --intrinsics fr1 gives the camera's (and resamples its lens).
  GASP_REQUIRE_DATA(dir, "tum/fr1_desk9");
  const std::string out = gasp::test::scratchDir();
  const std::string mine = out + "/my_camera";
  std::filesystem::create_directories(mine);
  std::filesystem::copy(dir + "/depth", mine + "/depth");
  std::filesystem::copy_file(dir + "/depth.txt", mine + "/depth.txt");
  auto run = runProgram("gasp-odometry", "--tum " + mine + " --max-frames 3 --out " + out + "/a.txt");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_TRUE(contains(run.output, "intrinsics: fx 525 fy 525 cx 319.5 cy 239.5 (640x480, preset ros")) << run.output;
  EXPECT_TRUE(contains(run.output, "warning: ") && contains(run.output, "ROS default intrinsics")) << run.output;
  run = runProgram("gasp-odometry", "--tum " + mine + " --max-frames 3 --intrinsics fr1 --out " + out + "/b.txt");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_TRUE(contains(run.output, "intrinsics: fx 517.3 fy 516.5 cx 318.6 cy 255.3 (640x480, option, undistorted)")) << run.output;
  EXPECT_FALSE(contains(run.output, "ROS default intrinsics")) << run.output;
  run = runProgram("gasp-odometry", "--tum " + mine + " --max-frames 3 --intrinsics fr1 --no-undistort --depth-scale 5000 --out " +
                                        out + "/c.txt");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_TRUE(contains(run.output, "(640x480, option)")) << run.output;
  // A camera file that is not there is bad input; the TUM-only options need --tum.
  run = runProgram("gasp-odometry", "--tum " + mine + " --intrinsics " + out + "/none.txt --out " + out + "/d.txt");
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_TRUE(contains(run.output, "none.txt")) << run.output;
  run = runProgram("gasp-odometry", "--rawlog x.rawlog --depth-scale 1000 --out " + out + "/e.txt");
  EXPECT_EQ(run.exit_code, 2) << run.output;
  run = runProgram("gasp-odometry", "--tum " + mine + " --depth-scale 0 --out " + out + "/f.txt");
  EXPECT_EQ(run.exit_code, 2) << run.output;
}

TEST(GaspOdometryProgram, BadInputExitsWith1OrAUsageCode) {
  const std::string out = gasp::test::scratchDir();
  const std::string sim = simulatedFolder(out);
  auto run = runProgram("gasp-odometry", "--tum " + out + "/nothing --out " + out + "/t.txt");
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_TRUE(contains(run.output, "error: ") && contains(run.output, "nothing")) << run.output;

  run = runProgram("gasp-odometry", "--tum " + sim + " --first 50 --out " + out + "/t.txt");
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_TRUE(contains(run.output, "first frame 50 but the folder has 30 frames")) << run.output;

  {
    std::ofstream garbage(out + "/garbage.rawlog");
    garbage << "not a rawlog";
  }
  run = runProgram("gasp-odometry", "--rawlog " + out + "/garbage.rawlog --out " + out + "/t.txt");
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_TRUE(contains(run.output, "garbage.rawlog")) << run.output;

  run = runProgram("gasp-odometry", "--out " + out + "/t.txt");
  EXPECT_EQ(run.exit_code, 2) << run.output;
  run = runProgram("gasp-odometry", "--tum " + sim);  // --out is required
  EXPECT_EQ(run.exit_code, 2) << run.output;
  run = runProgram("gasp-odometry", "--tum " + sim + " --every 0 --out " + out + "/t.txt");
  EXPECT_EQ(run.exit_code, 2) << run.output;
  run = runProgram("gasp-odometry", "--tum " + sim + " --max-frames 2 --out " + out + "/t2.txt --graph " + out +
                                        "/no/such/folder/g.graph");
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_TRUE(contains(run.output, "error: ") && contains(run.output, "g.graph")) << run.output;
  EXPECT_TRUE(contains(run.output, "does not exist")) << run.output;  // said before the run, in one line
  EXPECT_FALSE(contains(run.output, "MRPT exception")) << run.output;
  // Option values out of range are usage errors, said plainly (no wrap-round of negative counts).
  run = runProgram("gasp-odometry", "--tum " + sim + " --out " + out + "/t.txt --keyframe-angle 0");
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_TRUE(contains(run.output, "--keyframe-angle: must be greater than 0")) << run.output;
  run = runProgram("gasp-odometry", "--tum " + sim + " --out " + out + "/t.txt --first -1");
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_TRUE(contains(run.output, "--first: must be at least 0 (got -1)")) << run.output;
  run = runProgram("gasp-odometry", "--tum " + sim + " --out " + out + "/t.txt --rolling-shutter 1e9");
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_FALSE(std::filesystem::exists(out + "/t.txt"));
  // An output onto an input (the folder's ground truth), or one file for two outputs: refused
  // before the run, the input untouched.
  const auto gt_size = std::filesystem::file_size(sim + "/groundtruth.txt");
  run = runProgram("gasp-odometry", "--tum " + sim + " --out " + sim + "/../sim/groundtruth.txt");
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_TRUE(contains(run.output, "is an input of this run")) << run.output;
  EXPECT_EQ(std::filesystem::file_size(sim + "/groundtruth.txt"), gt_size);
  run = runProgram("gasp-odometry", "--tum " + sim + " --out " + out + "/t.txt --frames-csv " + out + "/t.txt");
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_TRUE(contains(run.output, "--frames-csv '" + out + "/t.txt': the same file as --out")) << run.output;
  EXPECT_FALSE(std::filesystem::exists(out + "/t.txt"));
  run = runProgram("gasp-odometry", "--tum " + sim + " --out " + out);  // a folder
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_TRUE(contains(run.output, "is a folder, not a file")) << run.output;
}

TEST(GaspOdometryProgram, NoScoreWhenNoFrameAfterTheFirstWasTracked) {
  // Frames 1-5 have no depth at all: their poses are predicted, so an ATE over them would score
  // predictions against the ground truth. The program says there is nothing to score.
  const std::string out = gasp::test::scratchDir();
  const std::string sim = simulatedFolder(out);
  std::filesystem::path first_path = gasp::TumDataset::open(sim).frame(0).depth_path;
  if (first_path.is_relative()) first_path = std::filesystem::path(sim) / first_path;
  const cv::Mat first = cv::imread(first_path.string(), cv::IMREAD_UNCHANGED);
  ASSERT_FALSE(first.empty());
  ASSERT_TRUE(cv::imwrite(sim + "/depth/blank.png", cv::Mat::zeros(first.size(), CV_16UC1)));
  std::ifstream in(sim + "/depth.txt");
  std::string text, line;
  int data_lines = 0;
  while (std::getline(in, line)) {
    if (!line.empty() && line[0] != '#' && data_lines++ > 0) line = line.substr(0, line.find(' ')) + " depth/blank.png";
    text += line + "\n";
  }
  in.close();
  std::ofstream(sim + "/depth.txt") << text;
  const auto run = runProgram("gasp-odometry", "--tum " + sim + " --max-frames 6 --out " + out + "/t.txt");
  EXPECT_EQ(run.exit_code, 3) << run.output;
  EXPECT_TRUE(contains(run.output, "tracked: 1\n")) << run.output;
  EXPECT_TRUE(contains(run.output, "evaluation: not possible: no frame after the first was tracked")) << run.output;
  EXPECT_FALSE(contains(run.output, "ate_rmse_m")) << run.output;
}

// A rawlog of LiDAR sweeps (gasp-simulate --sensor lidar16): gasp-odometry reads the sweeps with
// the params' lidar section, tracks every one and scores itself against the LiDAR's truth; and
// gasp-slam the same (its map outputs of sweeps: test_slam_program.cpp).
TEST(GaspOdometryProgram, ARawlogOfLidarSweepsIsTrackedAndScored) {
  const std::string out = gasp::test::scratchDir();
  const auto sim = runProgram("gasp-simulate", "--sensor lidar16 --frames 60 --rate 10 --out " + out + "/lidar");
  ASSERT_EQ(sim.exit_code, 0) << sim.output;
  const std::string input = "--rawlog " + out + "/lidar/lidar.rawlog --gt " + out + "/lidar/lidar_groundtruth.txt --max-frames 20";
  const auto run = runProgram("gasp-odometry", input + " --out " + out + "/traj.txt --frames-csv " + out + "/frames.csv");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_TRUE(contains(run.output, "frames: 20\n")) << run.output;
  EXPECT_TRUE(contains(run.output, "tracked: 20\n")) << run.output;
  EXPECT_EQ(gasp::readTumTrajectory(out + "/traj.txt").size(), 20u);
  const auto pos = run.output.find("ate_rmse_m: ");
  ASSERT_NE(pos, std::string::npos) << run.output;
  EXPECT_LT(std::stod(run.output.substr(pos + 12)), 0.05) << run.output;

  const auto slam = runProgram("gasp-slam", input + " --out " + out + "/slam.txt");
  ASSERT_EQ(slam.exit_code, 0) << slam.output;
  const auto slam_pos = slam.output.find("\nate_rmse_m: ");
  ASSERT_NE(slam_pos, std::string::npos) << slam.output;
  EXPECT_LT(std::stod(slam.output.substr(slam_pos + 13)), 0.05) << slam.output;
}
