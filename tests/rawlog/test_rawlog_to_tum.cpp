// gasp-rawlog2tum's library: a TUM folder through a rawlog and back keeps depth, colour, timestamps,
// intrinsics and ground truth exactly; what TUM cannot hold is left out and counted; bad input
// is an error that says what is wrong.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "gasp/core/error.h"
#include "gasp/core/tum_dataset.h"
#include "gasp/core/tum_trajectory.h"
#include "gasp/rawlog/rawlog_reader.h"
#include "gasp/rawlog/rawlog_to_tum.h"
#include "gasp/rawlog/rawlog_writer.h"
#include "gasp/rawlog/tum_to_rawlog.h"
#include "gasp_test_data.h"
#include "program_run.h"
#include "rawlog_test_frames.h"

namespace fs = std::filesystem;

namespace {

/// The gasp::Error message f() throws, or "no error".
template <class F>
std::string errorMessage(F&& f) {
  try {
    f();
  } catch (const gasp::Error& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST(RawlogToTum, ATumFolderThroughARawlogAndBackIsUnchanged) {
  GASP_REQUIRE_DATA(tum, "tum/fr1_desk9");
  const std::string dir = gasp::test::scratchDir();
  // As stored (no undistortion), so that the round trip can be compared pixel for pixel.
  gasp::TumDataset::Options as_stored;
  as_stored.undistort = false;
  const auto ds = gasp::TumDataset::open(tum, as_stored);
  gasp::TumToRawlogOptions to;
  to.undistort = false;
  const auto there = gasp::convertTumToRawlog(tum, dir + "/d9.rawlog", to);
  gasp::RawlogToTumOptions back;
  back.ground_truth_path = there.ground_truth_path;
  const auto s = gasp::convertRawlogToTum(dir + "/d9.rawlog", dir + "/d9", back);
  EXPECT_EQ(s.frames_written, 9u);
  EXPECT_EQ(s.frames_with_rgb, 9u);
  EXPECT_EQ(s.rgb_not_registered, 0u);
  EXPECT_EQ(s.pixels_beyond_range, 0u);
  EXPECT_EQ(s.sensor_label, "RGBD");
  EXPECT_TRUE(s.ground_truth);

  const auto out = gasp::TumDataset::open(dir + "/d9", as_stored);
  ASSERT_EQ(out.size(), ds.size());
  // The pinhole part; gasp-tum2rawlog --no-undistort drops the lens coefficients (docs/rawlog.md
  // "Distortion"), so the coefficients' way through is tested on MRPT's sample below.
  EXPECT_EQ(out.intrinsics(), ds.intrinsics());
  EXPECT_EQ(s.sensor_pose_dropped, 0u);  // gasp-tum2rawlog's scans have the identity sensorPose
  for (std::size_t i = 0; i < ds.size(); ++i) {
    EXPECT_NEAR(out.frame(i).timestamp, ds.frame(i).timestamp, 1e-6) << i;
    EXPECT_TRUE(gasp::test::sameMat(out.loadDepthRaw(i), ds.loadDepthRaw(i))) << "depth " << i;
    EXPECT_TRUE(gasp::test::sameMat(out.loadRgb(i), ds.loadRgb(i))) << "rgb " << i;
    ASSERT_TRUE(out.frame(i).T_world_camera.has_value()) << i;
    EXPECT_TRUE(out.frame(i).T_world_camera->isApprox(*ds.frame(i).T_world_camera, 1e-7)) << i;
  }
  // A second conversion into the same folder would mix two sequences: refused.
  EXPECT_THROW(gasp::convertRawlogToTum(dir + "/d9.rawlog", dir + "/d9", back), gasp::Error);
}

TEST(RawlogToTum, ColourNotRegisteredToTheDepthIsLeftOutAndCounted) {
  // MRPT's own sample: depth and intensity cameras with different intrinsics, depth in mm.
  const std::string path = "/usr/share/mrpt/datasets/tests_rgbd.rawlog";
  if (!fs::exists(path)) GTEST_SKIP() << path << " not found (package mrpt-common)";
  const std::string dir = gasp::test::scratchDir() + "/sample";
  const auto s = gasp::convertRawlogToTum(path, dir);
  EXPECT_EQ(s.frames_written, 1u);
  EXPECT_EQ(s.frames_with_rgb, 0u);
  EXPECT_EQ(s.rgb_not_registered, 1u);
  EXPECT_EQ(s.sensor_label, "OPENNI2");
  EXPECT_FALSE(fs::exists(dir + "/rgb.txt"));
  const auto out = gasp::TumDataset::open(dir);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_FALSE(out.frame(0).rgb_path.has_value());
  EXPECT_GT(out.loadDepth(0).cols, 0);
  // The depth camera's lens coefficients reach intrinsics.txt, and the folder is undistorted on loading.
  EXPECT_EQ(out.calibratedIntrinsics(), s.intrinsics);
  EXPECT_NE(out.calibratedIntrinsics().distortion[0], 0.0);
  EXPECT_EQ(out.intrinsics().distortion[0], 0.0);
}

TEST(RawlogToTum, SeveralSensorsOrTwoScansAtOneTimeLeaveNoHalfWrittenFolder) {
  const std::string dir = gasp::test::scratchDir();
  auto write = [&](const std::string& path, const std::vector<gasp::RgbdFrame>& frames) {
    gasp::RawlogWriter w(path);
    for (const auto& f : frames) w.write(f);
    w.close();
  };
  auto a = gasp::test::syntheticFrame(1.0), b = gasp::test::syntheticFrame(2.0), c = gasp::test::syntheticFrame(2.0);
  b.sensor_label = "OTHER";
  write(dir + "/two_sensors.rawlog", {a, gasp::test::syntheticFrame(1.5), b});
  write(dir + "/same_time.rawlog", {a, gasp::test::syntheticFrame(2.0), c});
  const std::string two_sensors = errorMessage([&] { gasp::convertRawlogToTum(dir + "/two_sensors.rawlog", dir + "/x"); });
  EXPECT_NE(two_sensors.find("several sensors"), std::string::npos) << two_sensors;
  EXPECT_FALSE(fs::exists(dir + "/x"));  // the two frames written before were removed again
  const std::string same_time = errorMessage([&] { gasp::convertRawlogToTum(dir + "/same_time.rawlog", dir + "/y"); });
  EXPECT_NE(same_time.find("two scans at timestamp 2.000000"), std::string::npos) << same_time;
  EXPECT_FALSE(fs::exists(dir + "/y"));
  // One sensor chosen: converted; the synthetic scans' robot frame is not the camera's, and said.
  gasp::RawlogToTumOptions one;
  one.sensor_label = a.sensor_label;
  const auto s = gasp::convertRawlogToTum(dir + "/two_sensors.rawlog", dir + "/z", one);
  EXPECT_EQ(s.frames_written, 2u);
  EXPECT_EQ(s.frames_other_sensor, 1u);
  EXPECT_EQ(s.sensor_pose_dropped, 2u);
  EXPECT_EQ(s.rgb_not_registered, 2u);  // the synthetic colour camera has its own fx
  // A folder that already holds part of a TUM folder is refused.
  fs::create_directories(dir + "/w");
  std::ofstream(dir + "/w/groundtruth.txt") << "# stale\n";
  EXPECT_THROW(gasp::convertRawlogToTum(dir + "/two_sensors.rawlog", dir + "/w", one), gasp::Error);
}

TEST(RawlogToTum, BadInputIsAnErrorThatSaysWhat) {
  GASP_REQUIRE_DATA(tum, "tum/fr1_desk9");
  const std::string dir = gasp::test::scratchDir();
  gasp::TumToRawlogOptions to;
  to.max_frames = 2;
  const auto there = gasp::convertTumToRawlog(tum, dir + "/two.rawlog", to);
  EXPECT_NE(errorMessage([&] { gasp::convertRawlogToTum(dir + "/missing.rawlog", dir + "/a"); }).find("missing.rawlog"),
            std::string::npos);
  gasp::RawlogToTumOptions other;
  other.sensor_label = "LIDAR";
  EXPECT_NE(errorMessage([&] { gasp::convertRawlogToTum(dir + "/two.rawlog", dir + "/b", other); })
                .find("no CObservation3DRangeScan with sensor label 'LIDAR'"),
            std::string::npos);
  // A bad trajectory fails before anything is written.
  std::ofstream(dir + "/bad_gt.txt") << "1305031453.374112 1 2 3\n";
  gasp::RawlogToTumOptions bad_gt;
  bad_gt.ground_truth_path = dir + "/bad_gt.txt";
  EXPECT_NE(errorMessage([&] { gasp::convertRawlogToTum(dir + "/two.rawlog", dir + "/c", bad_gt); }).find("bad_gt.txt"),
            std::string::npos);
  EXPECT_FALSE(fs::exists(dir + "/c/depth.txt"));
  // Files of the folder that exist already are not overwritten (nor removed on failure).
  const auto first = gasp::RawlogReader(dir + "/two.rawlog").next();
  char name[64];
  std::snprintf(name, sizeof name, "%.6f.png", first->timestamp);
  fs::create_directories(dir + "/e/depth");
  std::ofstream(dir + "/e/depth/" + name) << "mine";
  EXPECT_NE(errorMessage([&] { gasp::convertRawlogToTum(dir + "/two.rawlog", dir + "/e"); }).find("exists already"),
            std::string::npos);
  EXPECT_TRUE(fs::exists(dir + "/e/depth/" + name));
  // Scans out of time order, or without any depth, are errors.
  {
    gasp::RawlogWriter writer(dir + "/backwards.rawlog");
    writer.write(gasp::test::syntheticFrame(2.0));
    writer.write(gasp::test::syntheticFrame(1.0));
  }
  EXPECT_NE(errorMessage([&] { gasp::convertRawlogToTum(dir + "/backwards.rawlog", dir + "/f"); }).find("not after the previous"),
            std::string::npos);
  {
    gasp::RawlogWriter writer(dir + "/nodepth.rawlog");
    gasp::RgbdFrame blank = gasp::test::syntheticFrame(1.0);
    blank.depth_raw.setTo(0);
    blank.depth_m.setTo(0);
    writer.write(blank);
  }
  EXPECT_NE(errorMessage([&] { gasp::convertRawlogToTum(dir + "/nodepth.rawlog", dir + "/g"); }).find("none of the 1 scans"),
            std::string::npos);
  // max_frames.
  gasp::RawlogToTumOptions one;
  one.max_frames = 1;
  EXPECT_EQ(gasp::convertRawlogToTum(dir + "/two.rawlog", dir + "/d", one).frames_written, 1u);
}

TEST(RawlogToTum, TheProgramSaysWhatItWroteAndExitsWithTheRightCode) {
  GASP_REQUIRE_DATA(tum, "tum/fr1_desk9");
  const std::string dir = gasp::test::scratchDir();
  ASSERT_EQ(gasp::test::runProgram("gasp-tum2rawlog", tum + " " + dir + "/d9.rawlog --max-frames 3").exit_code, 0);
  const auto ok = gasp::test::runProgram("gasp-rawlog2tum", dir + "/d9.rawlog " + dir + "/out --gt " + dir +
                                                                "/d9_groundtruth.txt");
  ASSERT_EQ(ok.exit_code, 0) << ok.output;
  EXPECT_NE(ok.output.find("frames written:      3 (sensor 'RGBD')"), std::string::npos) << ok.output;
  EXPECT_NE(ok.output.find("ground truth:        groundtruth.txt"), std::string::npos) << ok.output;
  EXPECT_TRUE(fs::exists(dir + "/out/intrinsics.txt"));
  const auto again = gasp::test::runProgram("gasp-rawlog2tum", dir + "/d9.rawlog " + dir + "/out");
  EXPECT_EQ(again.exit_code, 1);
  EXPECT_NE(again.output.find("already holds a TUM folder"), std::string::npos) << again.output;
  EXPECT_EQ(gasp::test::runProgram("gasp-rawlog2tum", dir + "/missing.rawlog " + dir + "/x").exit_code, 1);
  EXPECT_NE(gasp::test::runProgram("gasp-rawlog2tum", "").exit_code, 0);  // usage
}
