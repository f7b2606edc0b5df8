#include "gasp/core/tum_dataset.h"

#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "gasp/core/error.h"
#include "gasp/core/image_file.h"
#include "gasp/core/text_file.h"

namespace fs = std::filesystem;

namespace gasp {

std::vector<std::pair<double, std::string>> readTumFileList(const std::string& path) {
  std::vector<std::pair<double, std::string>> entries;
  forEachDataLine(path, [&](const std::string& line, int line_no) {
    std::istringstream ss(line);
    std::string stamp, file, extra;
    ss >> stamp >> file;
    if (file.empty() || (ss >> extra))
      throw Error(path + ":" + std::to_string(line_no) + ": expected 'timestamp filename', got '" +
                  line + "'");
    const auto v = parseNumbers(stamp, path, line_no);
    // TUM's lists are in time order; a repeated or earlier stamp would pair the wrong ground truth.
    if (!entries.empty() && !(v.at(0) > entries.back().first))
      throw Error(path + ":" + std::to_string(line_no) + ": timestamp " + stamp +
                  " is not after the previous line's; the list must be in strictly increasing time order");
    entries.emplace_back(v.at(0), file);
  });
  return entries;
}

namespace {

/// TUM folder names carry the camera: rgbd_dataset_freiburg1_xyz, fr1_xyz, ...
std::optional<std::string> presetFromFolderName(const fs::path& dir) {
  std::string name = fs::weakly_canonical(dir).filename().string();
  std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return std::tolower(c); });
  for (const char* n : {"1", "2", "3"}) {
    const std::string digit(n);
    if (name.find("freiburg" + digit) != std::string::npos || name.rfind("fr" + digit, 0) == 0 ||
        name.find("_fr" + digit) != std::string::npos)
      return "fr" + digit;
  }
  return std::nullopt;
}

}  // namespace

TumDataset TumDataset::open(const std::string& dir, const Options& options) {
  if (!fs::is_directory(dir)) throw Error("TUM folder '" + dir + "' does not exist or is not a folder");
  TumDataset ds;
  ds.dir_ = dir;
  ds.options_ = options;
  const fs::path root(dir);

  if (options.intrinsics) {
    ds.intrinsics_ = *options.intrinsics;
    ds.intrinsics_source_ = "option";
  } else if (fs::exists(root / "intrinsics.txt")) {
    ds.intrinsics_ = CameraIntrinsics::load((root / "intrinsics.txt").string());
    ds.intrinsics_source_ = (root / "intrinsics.txt").string();
  } else if (const auto preset = presetFromFolderName(root)) {
    ds.intrinsics_ = CameraIntrinsics::fromPreset(*preset);
    ds.intrinsics_source_ = "preset " + *preset + " (from the folder name)";
  } else {
    ds.intrinsics_ = CameraIntrinsics::rosDefault();
    ds.intrinsics_source_ = "preset ros (default; pass intrinsics to override)";
    ds.intrinsics_guessed_ = true;
  }
  ds.intrinsics_.validate();
  CameraIntrinsics resampled = ds.intrinsics_;
  if (!options.undistort) resampled.distortion.fill(0.0);  // images used as stored
  ds.undistortion_ = sharedUndistortion(resampled);

  const fs::path depth_list = root / "depth.txt";
  if (!fs::exists(depth_list)) throw Error("TUM folder '" + dir + "' has no depth.txt");
  for (const auto& [stamp, file] : readTumFileList(depth_list.string())) {
    TumFrame f;
    f.timestamp = stamp;
    f.depth_path = (root / file).string();
    ds.frames_.push_back(f);
  }

  const fs::path rgb_list = root / "rgb.txt";
  if (fs::exists(rgb_list)) {
    const auto rgb = readTumFileList(rgb_list.string());
    std::vector<double> depth_stamps, rgb_stamps;
    for (const auto& f : ds.frames_) depth_stamps.push_back(f.timestamp);
    for (const auto& r : rgb) rgb_stamps.push_back(r.first);
    for (const auto& [id, ir] : associateTimestamps(depth_stamps, rgb_stamps, options.max_dt)) {
      ds.frames_[id].rgb_timestamp = rgb[ir].first;
      ds.frames_[id].rgb_path = (root / rgb[ir].second).string();
    }
  }

  const fs::path gt = root / "groundtruth.txt";
  if (fs::exists(gt)) {
    ds.ground_truth_ = readTumTrajectory(gt.string());
    for (auto& f : ds.frames_)
      if (const auto i = findNearest(ds.ground_truth_, f.timestamp, options.max_dt))
        f.T_world_camera = ds.ground_truth_[*i].T_world_camera;
  }
  return ds;
}

const TumFrame& TumDataset::frame(std::size_t i) const {
  if (i >= frames_.size())
    throw Error("frame index " + std::to_string(i) + " out of range: '" + dir_ + "' has " +
                std::to_string(frames_.size()) + " depth frames");
  return frames_[i];
}

std::string TumDataset::intrinsicsSummary() const {
  char buf[160];
  std::snprintf(buf, sizeof buf, "fx %g fy %g cx %g cy %g (%dx%d, ", intrinsics_.fx, intrinsics_.fy, intrinsics_.cx,
                intrinsics_.cy, intrinsics_.width, intrinsics_.height);
  return buf + intrinsics_source_ + (undistorts() ? ", undistorted)" : ")");
}

std::string TumDataset::intrinsicsWarning() const {
  if (!intrinsics_guessed_) return "";
  return dir_ + ": no intrinsics given, no intrinsics.txt in the folder, and its name names no TUM camera (fr1, fr2, "
                "fr3): the ROS default intrinsics (fx = fy = 525, cx 319.5, cy 239.5) are assumed; write the camera's "
                "into " + dir_ + "/intrinsics.txt (docs/formats.md) or pass --intrinsics where the program has it";
}

std::optional<Isometry3> TumDataset::groundTruthOf(std::size_t i, double offset_s) const {
  const TumFrame& f = frame(i);
  if (offset_s == 0.0) return f.T_world_camera;
  return groundTruthAt(f.timestamp + offset_s);
}

std::optional<Isometry3> TumDataset::groundTruthAt(double t) const {
  const auto k = findNearest(ground_truth_, t, options_.max_dt);
  if (!k) return std::nullopt;
  return ground_truth_[*k].T_world_camera;
}

std::size_t TumDataset::countWithGroundTruth() const {
  return static_cast<std::size_t>(std::count_if(
      frames_.begin(), frames_.end(), [](const TumFrame& f) { return f.T_world_camera.has_value(); }));
}

cv::Mat TumDataset::loadDepthRaw(std::size_t i) const {
  return undistortion_->applyToDepth(gasp::loadDepthRaw(frame(i).depth_path, intrinsics_.width, intrinsics_.height));
}

cv::Mat TumDataset::loadDepth(std::size_t i) const {
  return depthFromRaw(loadDepthRaw(i), options_.depth_units_per_metre);
}

cv::Mat TumDataset::loadRgb(std::size_t i) const {
  const auto& f = frame(i);
  if (!f.rgb_path) return {};
  cv::Mat img = readImage(*f.rgb_path, cv::IMREAD_COLOR, "rgb image");
  if (img.cols != intrinsics_.width || img.rows != intrinsics_.height)
    throw Error("rgb image '" + *f.rgb_path + "' is " + std::to_string(img.cols) + "x" + std::to_string(img.rows) +
                ", the depth images are " + std::to_string(intrinsics_.width) + "x" + std::to_string(intrinsics_.height));
  return undistortion_->applyToImage(img);
}

}  // namespace gasp
