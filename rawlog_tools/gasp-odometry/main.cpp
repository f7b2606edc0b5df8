// gasp-odometry: camera odometry over a depth sequence with GASP, and its pose graph.
//   gasp-odometry --tum DIR --out TRAJ.txt [--graph G.graph] [--frames-csv F.csv] [--params FILE] [options]
//   gasp-odometry --rawlog FILE.rawlog [--sensor LABEL] [--gt TRAJ.txt] --out TRAJ.txt [...]
// Each frame is registered to the current keyframe (gasp/odometry/odometry.h). A rawlog of a
// rotating LiDAR's sweeps is read as such (lidarOdometryParams(), the params' lidar section). Writes
// the trajectory of the depth camera (TUM format, optical frame, the first frame at the origin; a
// LiDAR's own frame for sweeps), and
// optionally the pose graph (MRPT VERTEX3 / EDGE3 lines, CNetworkOfPoses::saveToTextFile) and a
// line per frame. Where ground truth exists it prints the ATE and the RPE over 1 s (TUM's
// definitions, gasp/eval).
// Every output is opened before the run and written whole or not at all (run_outputs.h).
// Exit codes: 0 every frame tracked, 1 bad input (when the input ends with an error after some
// frames, the outputs are written for those frames, marked partial), 2 usage error, 3 written but
// some frames were not tracked (their poses are predicted; see --frames-csv).
#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdio>
#include <iostream>
#include <optional>

#include "gasp/core/error.h"
#include "gasp/core/stopwatch.h"
#include "gasp/core/tum_trajectory.h"
#include "gasp/mrpt/pose_graph.h"
#include "gasp/odometry/odometry.h"
#include "gasp/rawlog/depth_sequence.h"
#include "cli.h"
#include "params_options.h"
#include "frames_ahead.h"
#include "sequence_options.h"
#include "sequence_report.h"

int main(int argc, char** argv) {
  CLI::App app{"gasp-odometry: camera odometry over a depth sequence with GASP (each frame registered to a keyframe), "
               "its trajectory and pose graph"};
  gasp::DepthSequenceOptions input;
  std::string gt_path, out_path, graph_path, frames_csv;
  gasp::tools::ParamsOptions params_options;
  gasp::SlamParams all_params;
  if (!params_options.preload(argc, argv, all_params)) return 1;
  gasp::OdometryParams& params = all_params.odometry;  // the params file's sections segment to odometry
  gasp::tools::addSequenceOptions(app, input, gt_path, true);
  app.add_option("--out", out_path, "trajectory to write (TUM format: timestamp tx ty tz qx qy qz qw of the depth camera; required)");
  app.add_option("--graph", graph_path, "pose graph to write (MRPT VERTEX3/EDGE3 text; --rawlog: robot frames from the scans' sensorPose)");
  app.add_option("--frames-csv", frames_csv, "one line per frame: tracked, keyframe, reference, patches, inliers, times, reason");
  gasp::tools::addOdometryOptions(app, params);
  bool sequential = false;
  gasp::tools::addSequentialOption(app, sequential);
  params_options.add(app);
  if (const int code = gasp::tools::parseCommandLine(app, argc, argv); code >= 0) return code;
  if (const int code = gasp::tools::validOptionValues(all_params); code >= 0) return code;
  if (const int code = params_options.printIfAsked(all_params); code >= 0) return code;
  if (out_path.empty()) {
    std::cerr << "error: --out is required\nRun with --help for more information.\n";
    return 2;
  }
  if (input.tum_dir.empty() && input.rawlog_path.empty()) {
    std::cerr << "error: give --tum DIR or --rawlog FILE\n";
    return 2;
  }

  try {
    gasp::validate(params);
    gasp::tools::RunOutputs outputs({{"--out", out_path}, {"--graph", graph_path}, {"--frames-csv", frames_csv}},
                                    gasp::tools::sequenceInputs(input, gt_path));  // before the run, not after it
    gasp::DepthSequence sequence(input);
    // A LiDAR's sweeps: the pair's values from the params' lidar section (docs/lidar.md).
    const gasp::RgbdFrame* first = sequence.peek();
    const bool sweeps = first && first->isSweep();
    if (sweeps) params = gasp::lidarOdometryParams(all_params.lidar, params);
    gasp::DepthOdometry odometry(params);
    gasp::tools::reportIntrinsics(stdout, sequence.intrinsicsSummary(), sequence.intrinsicsWarning());
    const gasp::Trajectory gt = gt_path.empty() ? sequence.groundTruth() : gasp::readTumTrajectory(gt_path);
    // Each frame is segmented while the one before it is registered (frames_ahead.h).
    const auto run_start = std::chrono::steady_clock::now();
    const gasp::tools::SequenceEnd end = gasp::tools::forEachFrameWithViewAhead(sequence, params, sequential, [&](const gasp::RgbdFrame& frame, auto segmented) {
      const gasp::OdometryFrame& f =
          frame.isSweep() ? odometry.addFrame(frame.timestamp, *frame.sweep, std::move(segmented))
                          : odometry.addFrame(frame.timestamp, frame.depth_m, frame.depth_intrinsics, std::move(segmented));
      if (odometry.frames().size() % 50 == 0)
        std::fprintf(stderr, "frame %zu: %zu tracked of %zu\n", f.index, odometry.trackedCount(), odometry.frames().size());
    });
    const double wall_s = gasp::msSince(run_start) / 1000.0;

    const auto& frames = odometry.frames();
    gasp::OutputFile& out = outputs.at("--out");
    gasp::writeTumTrajectory(out.stream(), odometry.trajectory(),
                             gasp::tools::trajectoryHeader(sweeps ? "LiDAR trajectory by gasp-odometry (the LiDAR's own frame)"
                                                                  : "depth camera trajectory by gasp-odometry",
                                                           end));
    out.commit();
    if (auto* f = outputs.find("--frames-csv")) {
      gasp::tools::writeFramesCsv(f->stream(), frames);
      f->commit();
    }
    if (auto* graph_file = outputs.find("--graph")) {
      const auto g = gasp::toPoseGraph(frames, odometry.constraints(), sequence.robotCamera());
      gasp::tools::writeGraph(*graph_file, g.graph);
      std::printf("graph: %s (%zu nodes, %zu edges%s)\n", graph_path.c_str(), g.graph.nodes.size(), g.graph.edgeCount(),
                  g.skipped_constraints ? (", " + std::to_string(g.skipped_constraints) + " without a covariance left out").c_str() : "");
    }

    gasp::tools::printOdometrySummary(odometry);
    gasp::tools::printThroughput(frames, wall_s);
    std::printf("trajectory: %s\n", out_path.c_str());
    gasp::tools::printEvaluation(gt, odometry.trajectory(), odometry.trackedCount());
    if (const int code = gasp::tools::reportPartial(end); code >= 0) return code;
    if (odometry.trackedCount() < frames.size()) {
      std::printf("not_tracked: %zu frames (poses predicted; reasons in --frames-csv)\n",
                  frames.size() - odometry.trackedCount());
      return 3;
    }
  } catch (const std::exception& e) {  // gasp::Error, and MRPT's when the graph cannot be written
    std::cerr << "error: " << gasp::exceptionMessage(e) << '\n';
    return 1;
  }
  return 0;
}
