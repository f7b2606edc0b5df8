// gasp-odometry: camera odometry over a depth sequence with GASP, and its pose graph.
//   gasp-odometry --tum DIR --out TRAJ.txt [--graph G.graph] [--frames-csv F.csv] [options]
//   gasp-odometry --rawlog FILE.rawlog [--sensor LABEL] [--gt TRAJ.txt] --out TRAJ.txt [...]
// Each frame is registered to the current keyframe (gasp/odometry/odometry.h). Writes the
// trajectory of the depth camera (TUM format, optical frame, the first frame at the origin), and
// optionally the pose graph (MRPT VERTEX3 / EDGE3 lines, CNetworkOfPoses::saveToTextFile) and a
// line per frame. Where ground truth exists it prints the ATE and the RPE over 1 s (TUM's
// definitions, gasp/eval).
// Exit codes: 0 every frame tracked, 1 bad input, 2 usage error, 3 written but some frames were
// not tracked (their poses are predicted; see --frames-csv).
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <optional>
#include <vector>

#include "gasp/core/error.h"
#include "gasp/core/tum_dataset.h"
#include "gasp/core/tum_trajectory.h"
#include "gasp/eval/ate.h"
#include "gasp/eval/error_statistics.h"
#include "gasp/eval/rpe.h"
#include "gasp/mrpt/pose_graph.h"
#include "gasp/odometry/odometry.h"
#include "gasp/rawlog/rawlog_reader.h"

namespace {

double median(const std::vector<double>& v) { return gasp::eval::computeStatistics(v).median; }

void writeFramesCsv(const std::string& path, const std::vector<gasp::OdometryFrame>& frames) {
  std::ofstream out(path);
  if (!out) throw gasp::Error("cannot write " + path);
  out << "index,timestamp,tracked,keyframe,reference,patches,inliers,deskewed,segmentation_ms,registration_ms,reason\n";
  for (const auto& f : frames) {
    std::string reason = f.reason;
    std::replace(reason.begin(), reason.end(), '"', '\'');
    char buf[200];
    std::snprintf(buf, sizeof buf, "%zu,%.6f,%d,%d,%zu,%d,%d,%d,%.2f,%.2f,", f.index, f.timestamp, f.tracked ? 1 : 0,
                  f.keyframe ? 1 : 0, f.reference, f.patches, f.inliers, f.deskewed ? 1 : 0, f.segmentation_ms,
                  f.registration_ms);
    out << buf << '"' << reason << "\"\n";
  }
  if (!out) throw gasp::Error("cannot write " + path);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"gasp-odometry: camera odometry over a depth sequence with GASP (each frame registered to a keyframe), "
               "its trajectory and pose graph"};
  std::string tum_dir, rawlog_path, sensor_label, gt_path, out_path, graph_path, frames_csv;
  std::size_t first = 0, max_frames = 0, every = 1;
  gasp::OdometryParams params;
  auto* tum = app.add_option("--tum", tum_dir, "TUM RGB-D folder (frames in depth.txt order; its groundtruth.txt is the reference)");
  auto* rawlog = app.add_option("--rawlog", rawlog_path, "an MRPT rawlog: its CObservation3DRangeScan in file order")->excludes(tum);
  app.add_option("--sensor", sensor_label, "with --rawlog: only the scans with this sensorLabel")->needs(rawlog);
  app.add_option("--gt", gt_path, "with --rawlog: a TUM trajectory of the camera (optical frame), e.g. the "
                                  "OUT_groundtruth.txt gasp-tum2rawlog writes")->needs(rawlog);
  app.add_option("--out", out_path, "trajectory to write (TUM format: timestamp tx ty tz qx qy qz qw of the depth camera)")->required();
  app.add_option("--graph", graph_path, "pose graph to write (MRPT VERTEX3/EDGE3 text; --rawlog: robot frames from the scans' sensorPose)");
  app.add_option("--frames-csv", frames_csv, "one line per frame: tracked, keyframe, reference, patches, inliers, times, reason");
  app.add_option("--first", first, "first frame used (index among the input's frames)")->capture_default_str();
  app.add_option("--max-frames", max_frames, "at most this many frames (0 = all)")->capture_default_str();
  app.add_option("--every", every, "use every N-th frame (a wider baseline between frames)")->capture_default_str()->check(CLI::PositiveNumber);
  app.add_option("--keyframe-distance", params.keyframe_distance_m, "new keyframe beyond this distance from the last [m]")->capture_default_str();
  app.add_option("--keyframe-angle", params.keyframe_angle_deg, "new keyframe beyond this rotation from the last [deg]")->capture_default_str();
  app.add_option("--rolling-shutter", params.rolling_shutter_readout_s,
                 "deskew each frame for a rolling-shutter readout of S seconds with the last step's velocity (TUM Kinect: 0.03; 0 = off)")
      ->capture_default_str();
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;  // --help: 0; any usage error: 2
  }
  if (tum_dir.empty() && rawlog_path.empty()) {
    std::cerr << "error: give --tum DIR or --rawlog FILE\n";
    return 2;
  }

  try {
    gasp::validate(params);
    gasp::DepthOdometry odometry(params);
    gasp::Trajectory gt;
    std::optional<gasp::Isometry3> T_robot_camera;  // --rawlog: the scans' sensorPose (optical frame)
    std::size_t seen = 0, used = 0;
    const auto take = [&](std::size_t index) {
      return index >= first && (index - first) % every == 0 && (max_frames == 0 || used < max_frames);
    };
    const auto progress = [&](const gasp::OdometryFrame& f) {
      ++used;
      if (used % 50 == 0)
        std::fprintf(stderr, "frame %zu: %zu tracked of %zu\n", f.index, odometry.trackedCount(), odometry.frames().size());
    };
    if (!tum_dir.empty()) {
      const gasp::TumDataset ds = gasp::TumDataset::open(tum_dir);
      gt = ds.groundTruth();
      if (first >= ds.size())
        throw gasp::Error(tum_dir + ": --first " + std::to_string(first) + " but the folder has " + std::to_string(ds.size()) + " frames");
      for (std::size_t i = first; i < ds.size() && take(i); i += every)
        progress(odometry.addFrame(ds.frame(i).timestamp, ds.loadDepth(i), ds.intrinsics()));
    } else {
      if (!gt_path.empty()) gt = gasp::readTumTrajectory(gt_path);
      gasp::RawlogReader reader(rawlog_path);
      for (std::optional<gasp::RgbdFrame> f; (f = reader.next());) {
        if (!sensor_label.empty() && f->sensor_label != sensor_label) continue;
        const std::size_t index = seen++;
        if (index < first) continue;
        if (!take(index)) continue;
        if (!T_robot_camera) {
          T_robot_camera = f->T_robot_camera;
        } else if (!T_robot_camera->isApprox(f->T_robot_camera, 1e-9)) {
          throw gasp::Error(rawlog_path + ": scan " + std::to_string(index) +
                            " has another sensorPose than the first (one camera only; choose it with --sensor)");
        }
        progress(odometry.addFrame(f->timestamp, f->depth_m, f->depth_intrinsics));
        if (max_frames != 0 && used >= max_frames) break;  // read no scan beyond the last one used
      }
      if (used == 0)
        throw gasp::Error(rawlog_path + ": no scan to use (" + std::to_string(seen) + " scans" +
                          (sensor_label.empty() ? std::string() : " of sensor '" + sensor_label + "'") + ", --first " +
                          std::to_string(first) + ")");
    }

    const auto& frames = odometry.frames();
    gasp::writeTumTrajectory(out_path, odometry.trajectory(), "depth camera trajectory by gasp-odometry");
    if (!frames_csv.empty()) writeFramesCsv(frames_csv, frames);
    if (!graph_path.empty()) {
      const auto g = gasp::toPoseGraph(frames, odometry.constraints(), T_robot_camera.value_or(gasp::Isometry3::Identity()));
      g.graph.saveToTextFile(graph_path);
      std::printf("graph: %s (%zu nodes, %zu edges%s)\n", graph_path.c_str(), g.graph.nodes.size(), g.graph.edgeCount(),
                  g.skipped_constraints ? (", " + std::to_string(g.skipped_constraints) + " without a covariance left out").c_str() : "");
    }

    std::vector<double> seg, reg, total;
    for (const auto& f : frames)
      seg.push_back(f.segmentation_ms), reg.push_back(f.registration_ms), total.push_back(f.segmentation_ms + f.registration_ms);
    std::printf("frames: %zu\n", frames.size());
    std::printf("tracked: %zu\n", odometry.trackedCount());
    std::printf("keyframes: %zu\n", odometry.keyframeCount());
    std::printf("graph_components: %zu\n", odometry.componentCount());
    std::printf("median_ms_per_frame: %.1f (medians: segmentation %.1f, registration %.1f)\n", median(total),
                median(seg), median(reg));
    std::printf("trajectory: %s\n", out_path.c_str());
    if (!gt.empty()) {
      try {
        const auto ate = gasp::eval::computeAte(gt, odometry.trajectory());
        std::printf("ate_rmse_m: %.4f (%zu poses)\n", ate.translation.rmse, ate.translation.count);
        const auto rpe = gasp::eval::computeRpe(gt, odometry.trajectory());
        std::printf("rpe_1s_rmse: %.4f m, %.3f deg (%zu pairs)\n", rpe.translation.rmse, rpe.rotation_deg.rmse,
                    rpe.pairs.size());
      } catch (const gasp::Error& e) {
        std::printf("evaluation: not possible: %s\n", e.what());
      }
    }
    if (odometry.trackedCount() < frames.size()) {
      std::printf("not_tracked: %zu frames (poses predicted; reasons in --frames-csv)\n",
                  frames.size() - odometry.trackedCount());
      return 3;
    }
  } catch (const std::exception& e) {  // gasp::Error, and MRPT's when the graph cannot be written
    std::cerr << "error: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
