// Writing and reading rawlogs: synthetic frames (always) and the real fr1_desk9 folder, in both
// formats and with external storage; rawlog-edit's view of the result.
#include <gtest/gtest.h>
#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/maps/CSimplePointsMap.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/poses/CPose3D.h>
#include <mrpt/serialization/CArchive.h>

#include <algorithm>
#include <cmath>

#include <fstream>

#include <array>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "gasp/core/error.h"
#include "gasp/core/tum_dataset.h"
#include "gasp/core/tum_trajectory.h"
#include "gasp/rawlog/rawlog_reader.h"
#include "gasp/rawlog/rawlog_writer.h"
#include "gasp/rawlog/rgbd_frame_bytes.h"
#include "gasp/rawlog/tum_to_rawlog.h"
#include "gasp/sim/lidar.h"
#include "gasp/sim/scene.h"
#include "gasp_test_data.h"
#include "rawlog_test_frames.h"

namespace fs = std::filesystem;

namespace {

struct Variant {
  gasp::RawlogFormat format;
  bool external;
  int compress_level;
  const char* name;
};
const Variant kVariants[] = {
    {gasp::RawlogFormat::Observations, false, 1, "f2"},
    {gasp::RawlogFormat::ActionsSensoryFrames, false, 1, "f1"},
    {gasp::RawlogFormat::Observations, true, 1, "f2_external"},
    {gasp::RawlogFormat::ActionsSensoryFrames, true, 0, "f1_external_plain"},
};

/// Runs a command, returns its stdout (empty on failure to start).
std::string runCommand(const std::string& cmd) {
  std::string out;
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(cmd.c_str(), "r"), pclose);
  if (!pipe) return out;
  std::array<char, 4096> buf{};
  while (fgets(buf.data(), static_cast<int>(buf.size()), pipe.get())) out += buf.data();
  return out;
}

std::size_t countOccurrences(const std::string& text, const std::string& word) {
  std::size_t n = 0;
  for (auto p = text.find(word); p != std::string::npos; p = text.find(word, p + 1)) ++n;
  return n;
}

}  // namespace

TEST(RawlogRoundTrip, SyntheticFramesAllVariants) {
  const std::string dir = gasp::test::scratchDir();
  for (const auto& v : kVariants) {
    SCOPED_TRACE(v.name);
    const std::string path = dir + "/" + v.name + ".rawlog";
    std::vector<gasp::RgbdFrame> frames;
    for (int i = 0; i < 3; ++i) frames.push_back(gasp::test::syntheticFrame(100.0 + 0.033 * i));
    frames[1].rgb.release();  // a frame without rgb
    {
      gasp::RawlogWriter writer(path, {v.format, v.external, v.compress_level});
      for (const auto& f : frames) writer.write(f);
      EXPECT_EQ(writer.framesWritten(), 3u);
    }
    EXPECT_EQ(fs::is_directory(dir + "/" + v.name + "_Images"), v.external);

    gasp::RawlogReader reader(path);
    EXPECT_EQ(reader.format(), v.format);
    std::size_t i = 0;
    while (auto g = reader.next()) {
      ASSERT_LT(i, frames.size());
      const auto& f = frames[i];
      EXPECT_TRUE(gasp::test::sameMat(g->depth_raw, f.depth_raw));
      EXPECT_TRUE(gasp::test::sameMat(g->depth_m, f.depth_m));
      EXPECT_TRUE(gasp::test::sameMat(g->rgb, f.rgb)) << "frame " << i;
      EXPECT_EQ(g->depth_intrinsics, f.depth_intrinsics);
      EXPECT_NEAR(g->timestamp, f.timestamp, 1e-6);
      ++i;
    }
    EXPECT_EQ(i, 3u);
    EXPECT_EQ(reader.scansRead(), 3u);
    if (v.format == gasp::RawlogFormat::ActionsSensoryFrames) {
      EXPECT_EQ(reader.skipped().at("CActionCollection"), 3u);
    } else {
      EXPECT_TRUE(reader.skipped().empty()) << reader.skippedSummary();
    }
  }
}

// RawlogWriterOptions::points (gasp-tum2rawlog --points): each scan carries its 3D points, which
// MRPT's points maps insert (one point per valid pixel, at its pixel's distance), and GASP reads
// the frames as without them; a LiDAR's sweep in the same rawlog is a 3D scan of its points alone,
// which a reader of depth images leaves out and a reader of sweeps takes.
TEST(RawlogRoundTrip, PointsStoredForMrptsPointsMapsAndFramesReadAsWithout) {
  const std::string dir = gasp::test::scratchDir();
  std::vector<gasp::RgbdFrame> frames;
  for (int i = 0; i < 2; ++i) frames.push_back(gasp::test::syntheticFrame(100.0 + 0.033 * i));
  frames[1].depth_raw(cv::Rect(0, 0, 10, 10)).setTo(0);  // pixels without depth: no points
  frames[1].depth_m = gasp::depthFromRaw(frames[1].depth_raw, frames[1].depth_units_per_metre);
  for (const bool external : {false, true}) {
    SCOPED_TRACE(external ? "external" : "inline");
    const std::string path = dir + (external ? "/ext.rawlog" : "/inline.rawlog");
    gasp::RawlogWriterOptions options;
    options.external_storage = external;
    options.points = true;
    {
      gasp::RawlogWriter writer(path, options);
      for (const auto& f : frames) writer.write(f);
      gasp::Isometry3 T = gasp::Isometry3::Identity();
      T.translation().z() = 1.0;
      writer.write(gasp::sim::simulateLidarScan(gasp::sim::makeScene("room"), gasp::sim::lidarSensor(16), T, 1, 0),
                   "LIDAR");
    }
    {  // a reader of sweeps takes it (and the depth images too)
      gasp::RawlogReader all(path, true, "LIDAR");
      std::size_t sweeps = 0;
      while (auto f = all.next())
        if (f->isSweep()) {
          ++sweeps;
          EXPECT_EQ(f->sweep->range_m.rows, 16);
        }
      EXPECT_EQ(sweeps, 1u);
    }
    gasp::RawlogReader reader(path);
    std::size_t i = 0;
    while (auto g = reader.next()) {
      ASSERT_LT(i, frames.size());
      EXPECT_TRUE(gasp::test::sameMat(g->depth_raw, frames[i].depth_raw));
      EXPECT_TRUE(gasp::test::sameMat(g->depth_m, frames[i].depth_m));
      ++i;
    }
    EXPECT_EQ(i, frames.size());
    EXPECT_EQ(reader.skipped().at("CObservation3DRangeScan of 3D points without a range image"), 1u)
        << reader.skippedSummary();
    if (external) continue;
    // MRPT alone: the rawlog's scans and a points map from them.
    mrpt::io::CFileGZInputStream in(path);
    auto archive = mrpt::serialization::archiveFrom(in);
    for (const auto& f : frames) {
      mrpt::serialization::CSerializable::Ptr obj;
      archive >> obj;
      const auto scan = std::dynamic_pointer_cast<mrpt::obs::CObservation3DRangeScan>(obj);
      ASSERT_TRUE(scan);
      EXPECT_TRUE(scan->hasPoints3D);
      mrpt::maps::CSimplePointsMap map;
      ASSERT_TRUE(map.insertObservation(*scan, mrpt::poses::CPose3D()));
      // Each point at its pixel's distance from the camera (the frame has no mounting offset),
      // whatever MRPT's axes: the multiset of distances is the image's.
      std::vector<double> mrpt_range, image_range;
      for (std::size_t k = 0; k < map.size(); ++k) {
        float px = 0, py = 0, pz = 0;
        map.getPoint(k, px, py, pz);
        mrpt_range.push_back(std::sqrt(double(px) * px + double(py) * py + double(pz) * pz));
      }
      for (int v = 0; v < f.depth_m.rows; ++v)
        for (int u = 0; u < f.depth_m.cols; ++u)
          if (const float d = f.depth_m.at<float>(v, u); d > 0.0f)
            image_range.push_back(f.depth_intrinsics.unproject(u, v, d).norm());
      ASSERT_EQ(mrpt_range.size(), image_range.size());
      std::sort(mrpt_range.begin(), mrpt_range.end());
      std::sort(image_range.begin(), image_range.end());
      for (std::size_t k = 0; k < mrpt_range.size(); ++k) ASSERT_NEAR(mrpt_range[k], image_range[k], 1e-4) << k;
    }
  }
}

TEST(RawlogRoundTrip, ExternalStorageResolvedRelativeToTheRawlogNotTheWorkingDir) {
  const std::string dir = gasp::test::scratchDir();
  const gasp::RgbdFrame f = gasp::test::syntheticFrame(7.0);
  {
    gasp::RawlogWriter writer(dir + "/a/cam.rawlog", {gasp::RawlogFormat::Observations, true, 1});
    writer.write(f);
  }
  // The rawlog holds only file names: small; the data is in cam_Images.
  EXPECT_LT(fs::file_size(dir + "/a/cam.rawlog"), 2000u);
  EXPECT_TRUE(fs::exists(dir + "/a/cam_Images/RGBD_000000_depth.bin"));
  EXPECT_TRUE(fs::exists(dir + "/a/cam_Images/RGBD_000000_rgb.png"));
  // Move the whole thing elsewhere and read it from another working directory.
  fs::rename(dir + "/a", dir + "/b");
  const auto cwd = fs::current_path();
  fs::current_path(dir);
  const auto frames = gasp::readRawlogFrames(dir + "/b/cam.rawlog");
  fs::current_path(cwd);
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_TRUE(gasp::test::sameMat(frames[0].depth_raw, f.depth_raw));
  EXPECT_TRUE(gasp::test::sameMat(frames[0].rgb, f.rgb));

  // A cut or damaged external file (MRPT loads what it can of it) gives a gasp::Error naming it.
  const std::string bin = dir + "/b/cam_Images/RGBD_000000_depth.bin";
  fs::copy_file(bin, dir + "/whole.bin");
  fs::resize_file(bin, fs::file_size(bin) / 2);
  try {
    gasp::readRawlogFrames(dir + "/b/cam.rawlog");
    FAIL() << "expected gasp::Error";
  } catch (const gasp::Error& e) {
    EXPECT_NE(std::string(e.what()).find("RGBD_000000_depth.bin"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("truncated"), std::string::npos) << e.what();
  }
  // Garbage in place of the file (MRPT 2.5.8 would take its first bytes for the image size and
  // crash), and a whole file of another size: refused, naming the file.
  for (const std::string& content : {std::string("garbage\n"), std::string("\x10\x00\x00\x00\x08\x00\x00\x00", 8) +
                                                                    std::string(2 * 16 * 8, '\0')}) {
    std::ofstream(bin, std::ios::binary | std::ios::trunc) << content;
    try {
      gasp::readRawlogFrames(dir + "/b/cam.rawlog");
      ADD_FAILURE() << "expected gasp::Error";
    } catch (const gasp::Error& e) {
      EXPECT_NE(std::string(e.what()).find("RGBD_000000_depth.bin' is damaged or not this scan's"), std::string::npos)
          << e.what();
    }
  }
  fs::copy_file(dir + "/whole.bin", bin, fs::copy_options::overwrite_existing);
  EXPECT_EQ(gasp::readRawlogFrames(dir + "/b/cam.rawlog").size(), 1u);
  // A missing external file gives a gasp::Error naming it.
  fs::remove(dir + "/b/cam_Images/RGBD_000000_depth.bin");
  try {
    gasp::readRawlogFrames(dir + "/b/cam.rawlog");
    FAIL() << "expected gasp::Error";
  } catch (const gasp::Error& e) {
    EXPECT_NE(std::string(e.what()).find("RGBD_000000_depth.bin"), std::string::npos) << e.what();
  }
}

TEST(RawlogRoundTrip, TumFr1Desk9BothFormatsAndExternal) {
  GASP_REQUIRE_DATA(tum, "tum/fr1_desk9");
  const std::string dir = gasp::test::scratchDir();
  const auto ds = gasp::TumDataset::open(tum);
  for (const auto& v : kVariants) {
    SCOPED_TRACE(v.name);
    const std::string out = dir + "/" + v.name + ".rawlog";
    gasp::TumToRawlogOptions opt;
    opt.writer = {v.format, v.external, v.compress_level};
    const auto summary = gasp::convertTumToRawlog(tum, out, opt);
    EXPECT_EQ(summary.frames_written, 9u);
    EXPECT_EQ(summary.frames_with_rgb, 9u);
    EXPECT_EQ(summary.frames_with_ground_truth, 9u);
    EXPECT_EQ(summary.ground_truth_path, dir + "/" + v.name + "_groundtruth.txt");

    const auto frames = gasp::readRawlogFrames(out);
    ASSERT_EQ(frames.size(), 9u);
    for (std::size_t i = 0; i < frames.size(); ++i) {
      const auto& g = frames[i];
      EXPECT_TRUE(gasp::test::sameMat(g.depth_raw, ds.loadDepthRaw(i))) << "frame " << i;
      EXPECT_TRUE(gasp::test::sameMat(g.depth_m, ds.loadDepth(i))) << "frame " << i;
      EXPECT_TRUE(gasp::test::sameMat(g.rgb, ds.loadRgb(i))) << "frame " << i;
      EXPECT_DOUBLE_EQ(g.depth_units_per_metre, 5000.0);
      EXPECT_EQ(g.depth_intrinsics, ds.intrinsics());
      EXPECT_EQ(g.rgb_intrinsics, ds.intrinsics());
      EXPECT_NEAR(g.timestamp, ds.frame(i).timestamp, 1e-6);
      EXPECT_TRUE(g.T_depth_rgb.isApprox(gasp::Isometry3::Identity()));
      EXPECT_EQ(g.sensor_label, "RGBD");
    }
    const auto gt = gasp::readTumTrajectory(summary.ground_truth_path);
    ASSERT_EQ(gt.size(), 9u);
    for (std::size_t i = 0; i < gt.size(); ++i) {
      EXPECT_NEAR(gt[i].timestamp, ds.frame(i).timestamp, 1e-6);
      // writeTumTrajectory prints 9 decimals.
      EXPECT_TRUE(gt[i].T_world_camera.isApprox(*ds.frame(i).T_world_camera, 1e-7));
    }
  }
}

TEST(RawlogRoundTrip, TumOptionsNoRgbMaxFramesIntrinsics) {
  GASP_REQUIRE_DATA(tum, "tum/fr3_cabinet_kf");
  const std::string out = gasp::test::scratchDir() + "/cab.rawlog";
  gasp::TumToRawlogOptions opt;
  opt.with_rgb = false;
  opt.max_frames = 4;
  opt.intrinsics = gasp::CameraIntrinsics::rosDefault();
  const auto s = gasp::convertTumToRawlog(tum, out, opt);
  EXPECT_EQ(s.frames_written, 4u);
  EXPECT_EQ(s.frames_with_rgb, 0u);
  EXPECT_EQ(s.frames_with_ground_truth, 4u);
  const auto frames = gasp::readRawlogFrames(out);
  ASSERT_EQ(frames.size(), 4u);
  EXPECT_TRUE(frames[0].rgb.empty());
  EXPECT_EQ(frames[0].depth_intrinsics, gasp::CameraIntrinsics::rosDefault());
}

TEST(RawlogEdit, InfoListsTheObservations) {
  if (!fs::exists("/usr/bin/rawlog-edit")) GTEST_SKIP() << "/usr/bin/rawlog-edit not installed";
  const std::string dir = gasp::test::scratchDir();
  for (const auto& v : kVariants) {
    SCOPED_TRACE(v.name);
    const std::string path = dir + "/" + v.name + ".rawlog";
    {
      gasp::RawlogWriter writer(path, {v.format, v.external, v.compress_level});
      for (int i = 0; i < 5; ++i) writer.write(gasp::test::syntheticFrame(10.0 + i));
    }
    // Run in the rawlog's folder with a bare file name: MRPT 2.5.8 only finds "<name>_Images"
    // that way.
    const std::string info = runCommand("cd '" + dir + "' && /usr/bin/rawlog-edit --info -i '" +
                                        v.name + ".rawlog' 2>&1");
    const bool f1 = v.format == gasp::RawlogFormat::ActionsSensoryFrames;
    EXPECT_NE(info.find("Overall number of objects         : " + std::string(f1 ? "10" : "5")),
              std::string::npos) << info;
    EXPECT_NE(info.find(std::string("Actions/SensoryFrame format       : ") + (f1 ? "Yes" : "No")),
              std::string::npos) << info;
    EXPECT_NE(info.find("RGBD /      5"), std::string::npos) << info;
    if (v.external) {
      EXPECT_NE(info.find("Found external storage directory"), std::string::npos) << info;
    }
    // --info gives no class names; --list-timestamps does ("t label class" per observation).
    const std::string list = dir + "/" + v.name + "_list.txt";
    runCommand("/usr/bin/rawlog-edit --list-timestamps -i '" + path + "' --text-file-output '" +
               list + "' 2>&1");
    std::string text;
    {
      std::unique_ptr<FILE, int (*)(FILE*)> f(std::fopen(list.c_str(), "r"), std::fclose);
      ASSERT_TRUE(f) << "rawlog-edit wrote no " << list;
      std::array<char, 4096> buf{};
      while (std::fgets(buf.data(), static_cast<int>(buf.size()), f.get())) text += buf.data();
    }
    EXPECT_EQ(countOccurrences(text, "mrpt::obs::CObservation3DRangeScan"), 5u) << text;
  }
}

TEST(RgbdFrameBytes, FramesReadBackExactly) {
  // A camera frame (depth, stored depth, colour) and a sweep (rgbd_frame_bytes.h).
  gasp::RgbdFrame camera = gasp::test::syntheticFrame(12.5);
  camera.T_robot_camera.translation() << 0.1, -0.2, 0.3;
  camera.T_depth_rgb.translation() << 0.025, 0, 0;
  camera.sensor_label = "KINECT";
  gasp::RgbdFrame sweep;
  sweep.timestamp = 7.25;
  sweep.sensor_label = "VLP16";
  gasp::RangeScan s;
  s.timestamp = 7.25;
  s.model = "VLP16";
  s.range_m = (cv::Mat_<float>(2, 3) << 1.5f, 0.0f, 2.25f, 3.0f, 4.5f, 0.0f);
  s.elevation_rad = {-0.1, 0.1};
  s.azimuth_rad = {0.0, 2.0, 4.0};
  s.laser_of_row = {0, 1};
  s.sweep_duration_s = 0.1;
  s.T_robot_sensor.translation() << 0, 0, 1.2;
  sweep.sweep = s;
  for (const gasp::RgbdFrame& f : {camera, sweep}) {
    const gasp::RgbdFrame g = gasp::rgbdFrameFromBytes(gasp::rgbdFrameBytes(f));
    EXPECT_EQ(g.timestamp, f.timestamp);
    EXPECT_TRUE(gasp::test::sameMat(g.depth_m, f.depth_m));
    EXPECT_TRUE(gasp::test::sameMat(g.depth_raw, f.depth_raw));
    EXPECT_TRUE(gasp::test::sameMat(g.rgb, f.rgb));
    EXPECT_EQ(g.depth_units_per_metre, f.depth_units_per_metre);
    EXPECT_EQ(g.depth_intrinsics.fx, f.depth_intrinsics.fx);
    EXPECT_EQ(g.rgb_intrinsics.fx, f.rgb_intrinsics.fx);
    EXPECT_TRUE(g.T_robot_camera.matrix() == f.T_robot_camera.matrix());
    EXPECT_TRUE(g.T_depth_rgb.matrix() == f.T_depth_rgb.matrix());
    EXPECT_EQ(g.sensor_label, f.sensor_label);
    ASSERT_EQ(g.isSweep(), f.isSweep());
    if (f.isSweep()) {
      EXPECT_TRUE(gasp::test::sameMat(g.sweep->range_m, f.sweep->range_m));
      EXPECT_EQ(g.sweep->azimuth_rad, f.sweep->azimuth_rad);
      EXPECT_EQ(g.sweep->laser_of_row, f.sweep->laser_of_row);
      EXPECT_TRUE(g.sweep->T_robot_sensor.matrix() == f.sweep->T_robot_sensor.matrix());
    }
    const std::string bytes = gasp::rgbdFrameBytes(f);
    for (const std::string& bad : {bytes.substr(0, bytes.size() - 1), bytes + "x", "GRF2" + bytes.substr(4)}) {
      try {
        gasp::rgbdFrameFromBytes(bad);
        ADD_FAILURE() << "read";
      } catch (const gasp::Error& e) {
        EXPECT_EQ(std::string(e.what()).rfind("frame bytes: ", 0), 0u) << e.what();
      }
    }
  }
}
