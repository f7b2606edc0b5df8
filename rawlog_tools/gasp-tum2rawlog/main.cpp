/// \file main.cpp gasp-tum2rawlog: converts a TUM RGB-D folder into an MRPT rawlog of
/// CObservation3DRangeScan (raw uint16 depth, rangeUnits = 1/5000) plus the ground truth.
#include <CLI/CLI.hpp>

#include <exception>
#include <iostream>
#include <string>
#include <vector>

#include "gasp/core/error.h"
#include "gasp/rawlog/tum_to_rawlog.h"
#include "cli.h"
#include "params_options.h"

int main(int argc, char** argv) {
  CLI::App app{"Convert a TUM RGB-D folder into an MRPT rawlog of CObservation3DRangeScan; the "
               "ground truth goes to OUT_groundtruth.txt beside the rawlog."};
  // The params file is not used here; it is checked, and --print-params prints it, as in every program.
  gasp::tools::ParamsOptions params_options;
  gasp::SlamParams params;
  if (!params_options.preload(argc, argv, params)) return 1;
  if (const int code = params_options.printBeforeParse(params); code >= 0) return code;
  params_options.add(app);
  std::string tum_dir;
  std::string out_rawlog;
  std::string intrinsics;
  int format = 2;
  bool no_rgb = false;
  std::size_t max_frames = 0;
  bool external = false;
  app.add_option("TUM_DIR", tum_dir, "TUM folder with depth.txt (rgb.txt, groundtruth.txt optional)")
      ->required();
  app.add_option("OUT", out_rawlog, "rawlog to write (e.g. out.rawlog)")->required();
  app.add_option("--intrinsics", intrinsics,
                 "fr1|fr2|fr3|ros or an intrinsics file (default: DIR/intrinsics.txt, else guessed "
                 "from the folder name)");
  app.add_option("--format", format, "1: actions + sensory frames, 2: observations (default)")
      ->check(CLI::IsMember({1, 2}));
  app.add_flag("--no-rgb", no_rgb, "do not store the rgb images");
  bool no_undistort = false;
  app.add_flag("--no-undistort", no_undistort, "resample depth (and rgb) to the pinhole camera when the intrinsics have lens distortion (fr1, fr2: default); this flag uses the images as stored");
  app.add_option("--max-frames", max_frames, "convert at most N frames (0 = all)")->check(gasp::tools::atLeast(0));
  app.add_flag("--external", external, "store depth and rgb in OUT_Images/ (MRPT external storage)");
  bool points = false;
  app.add_flag("--points", points,
               "store each frame's 3D points too, which MRPT's points maps need (about 3.7 MB more per 640x480 frame "
               "before compression; as rawlog-edit --generate-3d-pointclouds)");
  if (const int code = gasp::tools::parseCommandLine(app, argc, argv); code >= 0) return code;

  try {
    std::vector<std::string> inputs = gasp::tools::tumFolderInputs(tum_dir);
    for (const std::string& f : gasp::tools::intrinsicsFileInput(intrinsics)) inputs.push_back(f);
    // Checked before the work (the writer opens OUT itself): not an input, a regular file or new.
    static_cast<void>(gasp::tools::RunOutputs(
        {{"OUT", out_rawlog}, {"OUT's ground truth", gasp::groundTruthPathForRawlog(out_rawlog)}}, inputs));
    gasp::TumToRawlogOptions options;
    if (!intrinsics.empty()) options.intrinsics = gasp::CameraIntrinsics::fromPresetOrFile(intrinsics);
    options.writer.format = gasp::rawlogFormatFromNumber(format);
    options.writer.external_storage = external;
    options.writer.points = points;
    options.with_rgb = !no_rgb;
    options.undistort = !no_undistort;
    options.max_frames = max_frames;
    const auto s = gasp::convertTumToRawlog(tum_dir, out_rawlog, options);

    const auto& K = s.intrinsics;
    std::cout << "frames written:      " << s.frames_written << "\n"
              << "  with rgb:          " << s.frames_with_rgb << "\n"
              << "  with ground truth: " << s.frames_with_ground_truth << "\n"
              << "intrinsics:          fx " << K.fx << " fy " << K.fy << " cx " << K.cx << " cy "
              << K.cy << " (" << K.width << "x" << K.height << ", " << s.intrinsics_source << ")\n"
              << "rawlog:              " << s.rawlog_path << " (format #" << format
              << ", depth uint16, rangeUnits = 1/5000 m)\n";
    if (!s.images_directory.empty())
      std::cout << "external images:     " << s.images_directory << "\n";
    std::cout << "ground truth:        "
              << (s.ground_truth_path.empty() ? std::string("none (no frame has ground truth)")
                                              : s.ground_truth_path)
              << "\n";
  } catch (const std::exception& e) {
    std::cerr << "error: " << gasp::exceptionMessage(e) << "\n";
    return 1;
  }
  return 0;
}
