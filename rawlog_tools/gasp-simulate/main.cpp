// gasp-simulate: synthetic depth sequences with ground truth, written as a TUM RGB-D folder, or
// LiDAR sweeps along the same path as an MRPT rawlog (--sensor lidar16|lidar32|lidar64).
// All logic lives in gasp::sim (modules/sim); see docs/simulator.md.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>
#include <iostream>
#include <string>
#include <vector>

#include "gasp/core/error.h"
#include "gasp/sim/camera_path.h"
#include "gasp/sim/object_move.h"
#include "gasp/sim/scene.h"
#include "gasp/sim/writer.h"
#include "cli.h"
#include "lidar_output.h"
#include "params_options.h"

int main(int argc, char** argv) {
  gasp::sim::SimulationOptions options;
  std::string out_dir;
  bool no_noise = false;
  bool list_scenes = false;
  std::vector<std::string> moves;
  std::string sensor = "camera";
  bool point_clouds = false;
  bool sweep_motion = false;

  CLI::App app{"Writes a synthetic depth sequence (ray-cast indoor scene, Kinect-like noise) with "
               "ground truth as a TUM RGB-D folder"};
  // The params file is not used here; it is checked, and --print-params prints it, as in every program.
  gasp::tools::ParamsOptions params_options;
  gasp::SlamParams params;
  if (!params_options.preload(argc, argv, params)) return 1;
  if (const int code = params_options.printBeforeParse(params); code >= 0) return code;
  params_options.add(app);
  app.add_option("--scene", options.scene, "Scene name (see --list-scenes)")->capture_default_str();
  app.add_option("--out", out_dir, "Output folder (created if needed)");
  app.add_option("--frames", options.frames, "Number of frames (8 to 20000)")
      ->capture_default_str()
      ->check(gasp::tools::within(gasp::sim::kMinPathFrames, gasp::sim::kMaxPathFrames));
  app.add_option("--seed", options.seed, "Noise seed")->capture_default_str()->check(gasp::tools::atLeast(0));
  app.add_option("--rate", options.rate_hz,
                 "Frame rate [Hz]: the timestamps' spacing (the path is the same; at 30 Hz the 60-frame path moves up to "
                 "3 m/s and 6 rad/s, at 5 Hz a sixth of that); 0.001 to 10000")
      ->capture_default_str()
      ->check(gasp::tools::within(gasp::sim::kMinRateHz, gasp::sim::kMaxRateHz));
  app.add_option("--move", moves,
                 "Move objects between frames (repeatable): PREFIX:DX,DY,DZ[,YAW_DEG]@FRAME moves every object whose "
                 "name starts with PREFIX (see surfaces.txt) by DX,DY,DZ metres in the world frame (z up), turned by "
                 "YAW_DEG about the vertical, from FRAME on; e.g. chair:0,-0.6,0@30 (docs/simulator.md)");
  app.add_option("--depth-bias", options.noise.radial_depth_bias,
                 "Systematic radial depth error K: depth scaled by 1 + K rho^2 (rho: the pixel's distance from the "
                 "principal point over the focal length), a plane bent into a bowl as by an uncalibrated Kinect; "
                 "0 = none, within [-0.2, 0.2] (docs/simulator.md)")
      ->capture_default_str()
      ->check(gasp::tools::within(-0.2, 0.2));
  app.add_option("--sensor", sensor,
                 "camera (a TUM folder), or lidar16, lidar32, lidar64: a spinning LiDAR of that many lasers along the "
                 "same path, written as OUT/lidar.rawlog (CObservationRotatingScan) and OUT/lidar_groundtruth.txt "
                 "(docs/simulator.md)")
      ->capture_default_str()
      ->check(CLI::IsMember({"camera", "lidar16", "lidar32", "lidar64"}));
  app.add_flag("--point-clouds", point_clouds,
               "with --sensor lidarN: write each sweep as a CObservationPointCloud (its points, no layout: how many "
               "drivers hand sweeps over) instead of a CObservationRotatingScan");
  app.add_flag("--sweep-motion", sweep_motion,
               "with --sensor lidarN: the sensor moves along the path during each sweep, each column fired from its "
               "own pose (a real spinning LiDAR's sweeps are skewed so); the ground truth is each sweep's start pose "
               "(docs/simulator.md)");
  app.add_flag("--no-noise", no_noise, "Exact ray-cast depth: no noise, quantisation or dropouts");
  app.add_flag("--list-scenes", list_scenes, "List the scenes and exit");
  if (const int code = gasp::tools::parseCommandLine(app, argc, argv); code >= 0) return code;

  try {
    if (list_scenes) {
      for (const auto& name : gasp::sim::sceneNames())
        std::cout << name << (name == gasp::sim::defaultSceneName() ? " (default)" : "") << ": "
                  << gasp::sim::makeScene(name).description << '\n';
      return 0;
    }
    if (out_dir.empty()) {  // a usage error, as every program's (exit 2)
      std::fprintf(stderr, "error: --out DIR is required\nRun with --help for more information.\n");
      return 2;
    }
    for (const auto& m : moves) options.moves.push_back(gasp::sim::parseObjectMove(m));
    if (no_noise) {  // the random noise off; a systematic --depth-bias stays
      const double bias = options.noise.radial_depth_bias;
      options.noise = gasp::sim::KinectNoiseModel::exact();
      options.noise.radial_depth_bias = bias;
    }

    if (point_clouds && sensor == "camera") {  // a usage error (exit 2)
      std::fprintf(stderr, "error: --point-clouds is a LiDAR's output; give --sensor lidar16, lidar32 or lidar64\n");
      return 2;
    }
    if (sweep_motion && sensor == "camera") {  // a usage error (exit 2)
      std::fprintf(stderr, "error: --sweep-motion is a LiDAR's; give --sensor lidar16, lidar32 or lidar64\n");
      return 2;
    }
    if (sensor != "camera") {
      if (options.noise.radial_depth_bias != 0.0) {  // the camera's error: a usage error (exit 2)
        std::fprintf(stderr, "error: --depth-bias is the depth camera's; it does not apply to --sensor %s\n", sensor.c_str());
        return 2;
      }
      gasp::sim::LidarSensor lidar = gasp::sim::lidarSensor(std::stoi(sensor.substr(5)));
      if (no_noise) lidar.range_sigma_m = 0.0, lidar.dropout = 0.0;
      const auto s = gasp::tools::writeLidarSequence(options, lidar, out_dir, point_clouds, sweep_motion);
      std::printf("scene:       %s\n", options.scene.c_str());
      std::printf("sweeps:      %d of %s%s%s (seed %llu, range noise %g m, %g %% dropouts), %.0f returns each on average\n",
                  s.sweeps, lidar.model.c_str(), point_clouds ? " as point clouds" : "", sweep_motion ? ", moving during each sweep" : "", static_cast<unsigned long long>(options.seed), lidar.range_sigma_m,
                  100.0 * lidar.dropout, s.returns_per_sweep);
      std::printf("written to:  %s\n             %s\n", s.rawlog.c_str(), s.groundtruth.c_str());
      return 0;
    }
    const auto summary = gasp::sim::writeSimulation(options, out_dir);
    std::printf("scene:      %s\n", summary.scene.c_str());
    std::printf("frames:     %d (seed %llu, %s)\n", summary.frames,
                static_cast<unsigned long long>(summary.seed), no_noise ? "no noise" : "Kinect noise");
    std::printf("valid:      %.1f%% of pixels\n", 100.0 * summary.valid_pixel_share);
    std::printf("segments:\n");
    for (const auto& s : summary.segments)
      std::printf("  %-18s frames %3d - %3d\n", s.name.c_str(), s.first_frame, s.last_frame);
    std::printf("written to: %s\n", summary.out_dir.c_str());
  } catch (const std::exception& e) {
    std::cerr << "error: " << gasp::exceptionMessage(e) << '\n';
    return 1;
  }
  return 0;
}
