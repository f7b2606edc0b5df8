#pragma once
/// \file sequence_options.h The command-line options gasp-odometry and gasp-slam share: the input
/// sequence and the odometry's parameters.
#include <CLI/CLI.hpp>

#include <string>
#include <vector>

#include "gasp/odometry/odometry_params.h"
#include "cli.h"
#include "gasp/rawlog/depth_sequence.h"

namespace gasp::tools {

/// --tum, --rawlog, --sensor, --gt (into gt_path), --first, --max-frames, --every, and for a TUM
/// folder --intrinsics, --depth-scale, --no-undistort. `sweeps`: a rawlog's LiDAR sweeps are
/// frames too (DepthSequenceOptions::sweeps).
inline void addSequenceOptions(CLI::App& app, DepthSequenceOptions& input, std::string& gt_path, bool sweeps = false) {
  input.sweeps = sweeps;
  auto* tum = app.add_option("--tum", input.tum_dir, "TUM RGB-D folder (frames in depth.txt order; its groundtruth.txt is the reference)");
  auto* rawlog = app.add_option("--rawlog", input.rawlog_path,
                                sweeps ? "an MRPT rawlog: its CObservation3DRangeScan, or its rotating LiDAR's sweeps "
                                         "(CObservationRotatingScan, CObservationVelodyneScan), in file order"
                                       : "an MRPT rawlog: its CObservation3DRangeScan in file order")
                     ->excludes(tum);
  app.add_option("--sensor", input.sensor_label, "with --rawlog: only the scans with this sensorLabel")->needs(rawlog);
  app.add_option("--gt", gt_path, "with --rawlog: a TUM trajectory of the camera (optical frame), e.g. the "
                                  "OUT_groundtruth.txt gasp-tum2rawlog writes, or of the LiDAR (its own frame, e.g. "
                                  "gasp-simulate's lidar_groundtruth.txt)")->needs(rawlog);
  app.add_option("--first", input.first, "first frame used (index among the input's frames)")
      ->capture_default_str()
      ->check(atLeast(0));
  app.add_option("--max-frames", input.max_frames, "at most this many frames (0 = all)")->capture_default_str()->check(atLeast(0));
  app.add_option("--every", input.every, "use every N-th frame (a wider baseline between frames)")->capture_default_str()->check(atLeast(1));
  app.add_option("--intrinsics", input.intrinsics,
                 "with --tum: the depth camera, fr1|fr2|fr3|ros or a file (docs/formats.md); default: the folder's "
                 "intrinsics.txt, else a preset guessed from its name, else ros (with a warning)")
      ->needs(tum)
      ->check(nonEmpty());
  app.add_option("--depth-scale", input.depth_units_per_metre, "with --tum: raw depth units per metre (TUM: 5000)")
      ->capture_default_str()
      ->needs(tum)
      ->check(above(0));
  app.add_flag("!--no-undistort", input.undistort, "with --tum: ignore lens distortion (images as stored)")->needs(tum);
}

/// The files the sequence options read (a TUM folder's lists and images, the rawlog and its
/// external images, --gt, an intrinsics file), which no output may overwrite (RunOutputs).
inline std::vector<std::string> sequenceInputs(const DepthSequenceOptions& input, const std::string& gt_path) {
  std::vector<std::string> files = tumFolderInputs(input.tum_dir);
  for (const std::string& f : rawlogInputs(input.rawlog_path)) files.push_back(f);
  if (!gt_path.empty()) files.push_back(gt_path);
  for (const std::string& f : intrinsicsFileInput(input.intrinsics)) files.push_back(f);
  return files;
}

/// --keyframe-distance, --keyframe-angle, --rolling-shutter, --no-scene-change.
inline void addOdometryOptions(CLI::App& app, OdometryParams& params) {
  app.add_option("--keyframe-distance", params.keyframe_distance_m, "new keyframe beyond this distance from the last [m]")
      ->capture_default_str()
      ->check(above(0));
  app.add_option("--keyframe-angle", params.keyframe_angle_deg, "new keyframe beyond this rotation from the last [deg]")
      ->capture_default_str()
      ->check(above(0));
  app.add_option("--rolling-shutter", params.rolling_shutter_readout_s,
                 "deskew each frame for a rolling-shutter readout of S seconds with the last step's velocity (TUM Kinect: 0.03; 0 = off)")
      ->capture_default_str()
      ->check(within(-1, 1));
  app.add_flag("!--no-scene-change", params.scene_change.enabled,
               "a frame the visibility check refuses is predicted, never taken with the looser scene-change limits "
               "under the constant-velocity prediction (docs/odometry.md, \"Scenes that change\")");
}

/// --sequential: no segmentation ahead (frames_ahead.h).
inline void addSequentialOption(CLI::App& app, bool& sequential) {
  app.add_flag("--sequential", sequential,
               "segment each frame only when it is added (by default the next two frames are segmented on threads of their own "
               "while the current one is registered; the poses are the same)");
}

}  // namespace gasp::tools
