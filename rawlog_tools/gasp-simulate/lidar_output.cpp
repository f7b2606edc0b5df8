#include "lidar_output.h"

#include <filesystem>
#include <fstream>
#include <string>

#include "gasp/core/error.h"
#include "gasp/core/tum_trajectory.h"
#include "gasp/rawlog/rawlog_writer.h"

namespace gasp::tools {

namespace {

constexpr const char* kTruthHeader = "ground truth of the simulated LiDAR (T_world_lidar), gasp-simulate";

/// A lidar.rawlog in the folder that gasp-simulate did not write (its ground truth does not carry
/// the simulator's header) is never replaced: it may be a recording.
void refuseForeignRawlog(const std::string& rawlog, const std::string& groundtruth) {
  std::error_code ec;
  if (!std::filesystem::exists(rawlog, ec)) return;
  std::ifstream in(groundtruth);
  std::string first;
  std::getline(in, first);
  if (first != std::string("# ") + kTruthHeader)
    throw Error("output folder holds '" + rawlog + "' that gasp-simulate did not write (a recording?); write into a new folder");
}

}  // namespace

LidarSequenceSummary writeLidarSequence(const sim::SimulationOptions& options, const sim::LidarSensor& sensor,
                                        const std::string& out_dir, bool as_point_clouds, bool sweep_motion) {
  const sim::Simulation simulation(options);
  std::error_code ec;
  std::filesystem::create_directories(out_dir, ec);
  if (ec) throw Error("cannot create the folder '" + out_dir + "': " + ec.message());
  LidarSequenceSummary summary;
  summary.rawlog = out_dir + "/lidar.rawlog";
  summary.groundtruth = out_dir + "/lidar_groundtruth.txt";
  refuseForeignRawlog(summary.rawlog, summary.groundtruth);
  RawlogWriter writer(summary.rawlog);
  Trajectory truth;
  double returns = 0.0;
  for (int i = 0; i < simulation.size(); ++i) {
    const StampedPose& pose = simulation.path().poses[static_cast<std::size_t>(i)];
    const Isometry3 T_world_lidar = sim::lidarPoseOfCamera(pose.T_world_camera);
    const auto at = [&](double t) { return sim::lidarPoseOfCamera(sim::poseAtTime(simulation.path().poses, pose.timestamp + t)); };
    RangeScan sweep = sweep_motion ? sim::simulateMovingLidarScan(simulation.scene(), sensor, at, options.seed, i)
                                   : sim::simulateLidarScan(simulation.scene(), sensor, T_world_lidar, options.seed, i);
    sweep.timestamp = pose.timestamp;
    returns += static_cast<double>(sweep.returnCount());
    if (as_point_clouds)
      writer.writePointCloud(sweep, "LIDAR");
    else
      writer.write(sweep, "LIDAR");
    truth.push_back({pose.timestamp, T_world_lidar});
  }
  writer.close();
  writeTumTrajectory(summary.groundtruth, truth, kTruthHeader);
  summary.sweeps = simulation.size();
  summary.returns_per_sweep = summary.sweeps > 0 ? returns / summary.sweeps : 0.0;
  return summary;
}

}  // namespace gasp::tools
