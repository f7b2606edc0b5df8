#include "gasp/rawlog/tum_to_rawlog.h"

#include <algorithm>
#include <filesystem>

#include "gasp/core/depth_image.h"
#include "gasp/core/error.h"
#include "gasp/core/tum_trajectory.h"
#include "gasp/rawlog/frame_convention.h"

namespace gasp {

std::string groundTruthPathForRawlog(const std::string& rawlog_path) {
  const std::filesystem::path p(rawlog_path);
  return (p.parent_path() / (p.stem().string() + "_groundtruth.txt")).string();
}

RgbdFrame frameFromTum(const TumDataset& dataset, std::size_t i, bool with_rgb,
                       const std::string& sensor_label) {
  const TumFrame& tf = dataset.frame(i);
  RgbdFrame f;
  f.timestamp = tf.timestamp;
  f.sensor_label = sensor_label;
  f.depth_raw = dataset.loadDepthRaw(i);
  f.depth_units_per_metre = dataset.depthUnitsPerMetre();
  f.depth_m = depthFromRaw(f.depth_raw, f.depth_units_per_metre);
  f.depth_intrinsics = dataset.intrinsics();
  f.rgb_intrinsics = dataset.intrinsics();
  // Camera looking along the robot's +X: MRPT sensorPose = identity.
  f.T_robot_camera = mrptCameraFromOptical();
  if (with_rgb && tf.rgb_path) {
    f.rgb = dataset.loadRgb(i);
    if (!f.rgb.empty()) {
      f.rgb_intrinsics.width = f.rgb.cols;
      f.rgb_intrinsics.height = f.rgb.rows;
    }
  }
  return f;
}

TumToRawlogSummary convertTumToRawlog(const std::string& tum_dir, const std::string& out_rawlog,
                                      const TumToRawlogOptions& options) {
  TumDataset::Options ds_options;
  ds_options.intrinsics = options.intrinsics;
  ds_options.undistort = options.undistort;
  const TumDataset dataset = TumDataset::open(tum_dir, ds_options);
  if (dataset.size() == 0) throw Error("TUM folder '" + tum_dir + "': depth.txt lists no frames");

  TumToRawlogSummary summary;
  summary.rawlog_path = out_rawlog;
  summary.intrinsics = dataset.intrinsics();
  summary.intrinsics_source = dataset.intrinsicsSource();

  const std::size_t n = options.max_frames > 0 ? std::min(options.max_frames, dataset.size())
                                               : dataset.size();
  Trajectory ground_truth;
  {
    RawlogWriter writer(out_rawlog, options.writer);
    for (std::size_t i = 0; i < n; ++i) {
      const RgbdFrame frame = frameFromTum(dataset, i, options.with_rgb, options.sensor_label);
      writer.write(frame);
      if (frame.hasRgb()) ++summary.frames_with_rgb;
      if (const auto& T = dataset.frame(i).T_world_camera) ground_truth.push_back({frame.timestamp, *T});
    }
    writer.close();
    summary.frames_written = writer.framesWritten();
    if (options.writer.external_storage) summary.images_directory = writer.imagesDirectory();
  }

  summary.frames_with_ground_truth = ground_truth.size();
  const std::string gt_path = groundTruthPathForRawlog(out_rawlog);
  if (!ground_truth.empty()) {
    writeTumTrajectory(gt_path, ground_truth,
                       "ground truth of " + out_rawlog + " (depth timestamps; from " + tum_dir +
                           "/groundtruth.txt)");
    summary.ground_truth_path = gt_path;
  } else {
    std::error_code ec;
    std::filesystem::remove(gt_path, ec);  // no stale file from an earlier run
  }
  return summary;
}

}  // namespace gasp
