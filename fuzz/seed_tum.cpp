// fuzz_seed_tum (not a fuzz target; fuzz/make_seeds.sh calls it):
//   fuzz_seed_tum SRC_DIR DST_DIR FRAMES WIDTH HEIGHT
// The first FRAMES depth frames of a TUM folder (and their nearest rgb frames, the ground truth of
// their time span, the intrinsics scaled) as a TUM folder of WIDTHxHEIGHT images: gasp-tum2rawlog
// over it makes rawlogs of a few KB, the seeds of fuzz_rawlog; its files seed the other targets.
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>

#include "gasp/core/depth_image.h"
#include "gasp/core/error.h"
#include "gasp/core/image_file.h"
#include "gasp/core/tum_dataset.h"
#include "gasp/core/tum_trajectory.h"

namespace fs = std::filesystem;

namespace {

void tinyTum(const std::string& src, const std::string& dst, int frames, int width, int height) {
  gasp::TumDataset::Options options;
  options.undistort = false;  // the images as stored; the intrinsics keep their distortion
  const gasp::TumDataset ds = gasp::TumDataset::open(src, options);
  if (ds.size() == 0) throw gasp::Error(src + ": no depth frames");
  fs::create_directories(fs::path(dst) / "depth");
  fs::create_directories(fs::path(dst) / "rgb");
  gasp::CameraIntrinsics k = ds.calibratedIntrinsics();
  const double sx = static_cast<double>(width) / k.width, sy = static_cast<double>(height) / k.height;
  k.fx *= sx, k.cx = (k.cx + 0.5) * sx - 0.5, k.fy *= sy, k.cy = (k.cy + 0.5) * sy - 0.5;
  k.width = width, k.height = height;
  k.save(dst + "/intrinsics.txt");
  std::ofstream depth_list(dst + "/depth.txt"), rgb_list(dst + "/rgb.txt");
  depth_list << "# depth maps (fuzz seed: " << width << "x" << height << " from " << src << ")\n# timestamp filename\n";
  rgb_list << "# color images\n# timestamp filename\n";
  const int n = std::min<int>(frames, static_cast<int>(ds.size()));
  for (int i = 0; i < n; ++i) {
    const gasp::TumFrame& f = ds.frame(static_cast<std::size_t>(i));
    cv::Mat depth;
    cv::resize(gasp::loadDepthRaw(f.depth_path), depth, cv::Size(width, height), 0, 0, cv::INTER_NEAREST);
    const std::string depth_name = "depth/" + fs::path(f.depth_path).filename().string();
    gasp::writeImage(dst + "/" + depth_name, depth, "depth image");
    char stamp[32];
    std::snprintf(stamp, sizeof stamp, "%.6f", f.timestamp);
    depth_list << stamp << ' ' << depth_name << '\n';
    if (f.rgb_path && f.rgb_timestamp) {
      cv::Mat rgb;
      cv::resize(gasp::readImage(*f.rgb_path, cv::IMREAD_COLOR, "rgb image"), rgb, cv::Size(width, height), 0, 0,
                 cv::INTER_AREA);
      const std::string rgb_name = "rgb/" + fs::path(*f.rgb_path).filename().string();
      gasp::writeImage(dst + "/" + rgb_name, rgb, "rgb image");
      std::snprintf(stamp, sizeof stamp, "%.6f", *f.rgb_timestamp);
      rgb_list << stamp << ' ' << rgb_name << '\n';
    }
  }
  const double t0 = ds.frame(0).timestamp - 0.05, t1 = ds.frame(static_cast<std::size_t>(n - 1)).timestamp + 0.05;
  gasp::Trajectory gt;
  for (const auto& p : ds.groundTruth())
    if (p.timestamp >= t0 && p.timestamp <= t1) gt.push_back(p);
  if (!gt.empty()) gasp::writeTumTrajectory(dst + "/groundtruth.txt", gt, "ground truth trajectory (fuzz seed)");
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 6) {
    std::cerr << "usage: fuzz_seed_tum SRC_DIR DST_DIR FRAMES WIDTH HEIGHT\n";
    return 2;
  }
  try {
    tinyTum(argv[1], argv[2], std::stoi(argv[3]), std::stoi(argv[4]), std::stoi(argv[5]));
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
