#include "gasp/rawlog/rawlog_to_tum.h"

#include <opencv2/imgcodecs.hpp>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <set>
#include <vector>

#include "gasp/core/depth_image.h"
#include "gasp/core/error.h"
#include "gasp/core/output_file.h"
#include "gasp/core/image_file.h"
#include "gasp/core/tum_trajectory.h"
#include "gasp/rawlog/frame_convention.h"
#include "gasp/rawlog/rawlog_reader.h"

namespace fs = std::filesystem;

namespace gasp {

namespace {

/// "1305031452.791720" (TUM's six decimals).
std::string stamp(double t) {
  char b[64];
  std::snprintf(b, sizeof b, "%.6f", t);
  return b;
}

void makeDir(const fs::path& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir))
    throw Error("cannot create folder '" + dir.string() + "'" + (ec ? ": " + ec.message() : std::string()));
}

void writeImage(const fs::path& path, const cv::Mat& image) { gasp::writeImage(path.string(), image, "image"); }

/// What one conversion created, removed again when it fails (no half-written folder is left).
class CreatedPaths {
 public:
  void dir(const fs::path& p) {
    if (!fs::exists(p)) {
      makeDir(p);
      paths_.push_back(p);
    }
  }
  void file(const fs::path& p) { paths_.push_back(p); }
  void keep() { paths_.clear(); }
  ~CreatedPaths() {
    std::error_code ec;
    for (auto it = paths_.rbegin(); it != paths_.rend(); ++it) fs::remove(*it, ec);  // dirs are empty by then
  }

 private:
  std::vector<fs::path> paths_;
};

}  // namespace

RawlogToTumSummary convertRawlogToTum(const std::string& rawlog_path, const std::string& out_dir,
                                      const RawlogToTumOptions& options) {
  const fs::path root(out_dir);
  for (const char* name : {"depth.txt", "rgb.txt", "groundtruth.txt", "intrinsics.txt"})
    if (fs::exists(root / name))
      throw Error("'" + out_dir + "' already holds a TUM folder (" + name + "): write into a new folder");
  // The trajectory first: a bad file fails before anything is written.
  Trajectory ground_truth;
  if (!options.ground_truth_path.empty()) ground_truth = readTumTrajectory(options.ground_truth_path);

  RawlogReader reader(rawlog_path);
  CreatedPaths created;
  created.dir(root);
  RawlogToTumSummary s;
  std::set<std::string> stamps;
  double last_timestamp = 0.0;
  std::optional<OutputFile> depth_txt, rgb_txt;  // published whole at the end
  constexpr double kMaxUnits = std::numeric_limits<std::uint16_t>::max();  // depthToRaw() writes 0 beyond
  while (auto f = reader.next()) {
    if (!options.sensor_label.empty() && f->sensor_label != options.sensor_label) {
      ++s.frames_other_sensor;
      continue;
    }
    if (s.frames_written > 0 && f->sensor_label != s.sensor_label)
      throw Error(rawlog_path + ": 3D range scans of several sensors ('" + s.sensor_label + "', '" +
                  f->sensor_label + "'): choose one (sensor label)");
    if (s.frames_written == 0) {
      s.sensor_label = f->sensor_label;
      s.intrinsics = f->depth_intrinsics;
      created.dir(root / "depth");
      created.file(root / "intrinsics.txt");
      s.intrinsics.save((root / "intrinsics.txt").string());
      created.file(root / "depth.txt");
      depth_txt.emplace((root / "depth.txt").string(), "depth list");
      depth_txt->stream() << "# depth maps\n# converted from " << rawlog_path << " by gasp-rawlog2tum\n# timestamp filename\n";
    } else if (f->depth_intrinsics != s.intrinsics) {
      throw Error(rawlog_path + ": scan " + std::to_string(reader.scansRead() - 1) +
                  " has other depth intrinsics than the first: a TUM folder holds one camera");
    }
    const std::string t = stamp(f->timestamp);
    if (!stamps.insert(t).second) throw Error(rawlog_path + ": two scans at timestamp " + t);
    // TUM's lists are in time order (GASP's readers refuse anything else).
    if (s.frames_written > 0 && !(f->timestamp > last_timestamp))
      throw Error(rawlog_path + ": scan " + std::to_string(reader.scansRead() - 1) + " at " + t +
                  " is not after the previous one: a TUM folder's frames are in time order");
    last_timestamp = f->timestamp;
    std::size_t written_pixels = 0;
    for (int r = 0; r < f->depth_m.rows; ++r)
      for (int c = 0; c < f->depth_m.cols; ++c) {
        const float z = f->depth_m.at<float>(r, c);
        const bool beyond = isValidDepth(z) && std::round(z * kTumDepthUnitsPerMetre) > kMaxUnits;
        s.pixels_beyond_range += beyond;
        written_pixels += isValidDepth(z) && !beyond;
      }
    s.frames_without_depth += written_pixels == 0;
    s.sensor_pose_dropped += !f->T_robot_camera.isApprox(mrptCameraFromOptical(), 1e-12);
    for (const fs::path& p : {root / "depth" / (t + ".png"), root / "rgb" / (t + ".png")})
      if (fs::exists(p)) throw Error("'" + p.string() + "' exists already: write into a new folder");
    created.file(root / "depth" / (t + ".png"));
    saveDepth((root / "depth" / (t + ".png")).string(), f->depth_m, kTumDepthUnitsPerMetre);
    depth_txt->stream() << t << " depth/" << t << ".png\n";
    if (options.with_rgb && !f->rgb.empty()) {
      const bool registered =
          f->rgb_intrinsics == f->depth_intrinsics && f->T_depth_rgb.isApprox(Isometry3::Identity(), 1e-12);
      if (!registered) {
        ++s.rgb_not_registered;
      } else {
        if (s.frames_with_rgb == 0) {
          created.dir(root / "rgb");
          created.file(root / "rgb.txt");
          rgb_txt.emplace((root / "rgb.txt").string(), "rgb list");
          rgb_txt->stream() << "# color images\n# converted from " << rawlog_path << " by gasp-rawlog2tum\n# timestamp filename\n";
        }
        created.file(root / "rgb" / (t + ".png"));
        writeImage(root / "rgb" / (t + ".png"), f->rgb);
        rgb_txt->stream() << t << " rgb/" << t << ".png\n";
        ++s.frames_with_rgb;
      }
    }
    ++s.frames_written;
    if (options.max_frames > 0 && s.frames_written >= options.max_frames) break;
  }
  if (s.frames_written == 0)
    throw Error(rawlog_path + ": no CObservation3DRangeScan" +
                (options.sensor_label.empty() ? std::string() : " with sensor label '" + options.sensor_label + "'") +
                " (other objects: " + reader.skippedSummary() + ")");
  if (s.frames_without_depth == s.frames_written)
    throw Error(rawlog_path + ": none of the " + std::to_string(s.frames_written) +
                " scans has a depth GASP can write (0 to 13.107 m; rangeUnits and the range image give none)");
  depth_txt->commit();
  if (rgb_txt) rgb_txt->commit();
  if (!options.ground_truth_path.empty()) {
    created.file(root / "groundtruth.txt");
    writeTumTrajectory((root / "groundtruth.txt").string(), ground_truth,
                       "ground truth trajectory (camera poses), copied from " + options.ground_truth_path);
    s.ground_truth = true;
  }
  s.other_objects = reader.skipped();
  created.keep();
  return s;
}

}  // namespace gasp
