/// \file main.cpp gasp-rawlog2tum: the CObservation3DRangeScan of an MRPT rawlog as a TUM RGB-D
/// folder (depth PNGs at 5000 units per metre, depth.txt, intrinsics.txt, registered rgb, an
/// optional ground truth), so that the TUM tools run on it (rawlog_to_tum.h).
#include <CLI/CLI.hpp>

#include <exception>
#include <iostream>
#include <string>

#include "gasp/core/error.h"
#include "gasp/rawlog/rawlog_to_tum.h"
#include "cli.h"
#include "params_options.h"

int main(int argc, char** argv) {
  CLI::App app{"Convert the CObservation3DRangeScan of an MRPT rawlog into a TUM RGB-D folder (depth.txt, "
               "depth/*.png at 5000 units per metre, intrinsics.txt, registered rgb, groundtruth.txt from --gt)."};
  // The params file is not used here; it is checked, and --print-params prints it, as in every program.
  gasp::tools::ParamsOptions params_options;
  gasp::SlamParams params;
  if (!params_options.preload(argc, argv, params)) return 1;
  if (const int code = params_options.printBeforeParse(params); code >= 0) return code;
  params_options.add(app);
  std::string rawlog, out_dir;
  gasp::RawlogToTumOptions options;
  bool no_rgb = false;
  app.add_option("RAWLOG", rawlog, "the rawlog to read")->required();
  app.add_option("OUT_DIR", out_dir, "the TUM folder to write (created; must not hold a depth.txt yet)")->required();
  app.add_option("--sensor", options.sensor_label,
                 "only the scans with this sensorLabel (needed when the rawlog has several 3D sensors)");
  app.add_option("--gt", options.ground_truth_path,
                 "a TUM trajectory of the camera poses to copy to groundtruth.txt (e.g. gasp-tum2rawlog's OUT_groundtruth.txt)");
  app.add_flag("--no-rgb", no_rgb, "do not write the colour images");
  app.add_option("--max-frames", options.max_frames, "convert at most N scans (0 = all)")->check(gasp::tools::atLeast(0));
  if (const int code = gasp::tools::parseCommandLine(app, argc, argv); code >= 0) return code;
  options.with_rgb = !no_rgb;
  try {
    const auto s = gasp::convertRawlogToTum(rawlog, out_dir, options);
    const auto& K = s.intrinsics;
    std::cout << "frames written:      " << s.frames_written << " (sensor '" << s.sensor_label << "')\n"
              << "  with rgb:          " << s.frames_with_rgb << "\n";
    if (s.rgb_not_registered > 0)
      std::cout << "  rgb left out:      " << s.rgb_not_registered
                << " (not registered to the depth: other intrinsics or an offset; TUM assumes registered rgb)\n";
    if (s.frames_other_sensor > 0) std::cout << "other sensors:       " << s.frames_other_sensor << " scans skipped\n";
    if (s.sensor_pose_dropped > 0)
      std::cout << "robot frame:         " << s.sensor_pose_dropped
                << " scans with a sensorPose not kept (a TUM folder holds camera poses only)\n";
    if (s.frames_without_depth > 0)
      std::cout << "without depth:       " << s.frames_without_depth << " frames (no depth pixel from 0 to 13.107 m)\n";
    if (s.pixels_beyond_range > 0)
      std::cout << "beyond 13.107 m:     " << s.pixels_beyond_range << " depth pixels written as 0 (no data)\n";
    std::cout << "intrinsics:          fx " << K.fx << " fy " << K.fy << " cx " << K.cx << " cy " << K.cy << " ("
              << K.width << "x" << K.height << ", written to intrinsics.txt)\n"
              << "ground truth:        " << (s.ground_truth ? "groundtruth.txt" : "none (no --gt)") << "\n";
    if (!s.other_objects.empty()) {
      std::cout << "other objects:       ";
      bool first = true;
      for (const auto& [name, n] : s.other_objects) std::cout << (first ? "" : ", ") << n << " x " << name, first = false;
      std::cout << " (skipped)\n";
    }
  } catch (const std::exception& e) {
    std::cerr << "error: " << gasp::exceptionMessage(e) << "\n";
    return 1;
  }
  return 0;
}
