#include <gtest/gtest.h>

#include <fstream>

#include "gasp/core/camera_intrinsics.h"
#include "gasp/core/error.h"
#include "gasp_test_data.h"

using gasp::CameraIntrinsics;

TEST(CameraIntrinsics, PresetsMatchTumCalibration) {
  const auto fr1 = CameraIntrinsics::fromPreset("fr1");
  EXPECT_DOUBLE_EQ(fr1.fx, 517.3);
  EXPECT_DOUBLE_EQ(fr1.cy, 255.3);
  const auto fr3 = CameraIntrinsics::fromPreset("freiburg3");
  EXPECT_DOUBLE_EQ(fr3.fy, 539.2);
  const auto ros = CameraIntrinsics::fromPreset("ros");
  EXPECT_DOUBLE_EQ(ros.fx, 525.0);
  EXPECT_DOUBLE_EQ(ros.cx, 319.5);
  EXPECT_THROW(CameraIntrinsics::fromPreset("fr4"), gasp::Error);
}

TEST(CameraIntrinsics, ProjectInvertsUnproject) {
  const auto k = CameraIntrinsics::tumFreiburg2();
  const Eigen::Vector3d p = k.unproject(100.25, 400.5, 2.5);
  double u = 0, v = 0;
  ASSERT_TRUE(k.project(p, u, v));
  EXPECT_NEAR(u, 100.25, 1e-9);
  EXPECT_NEAR(v, 400.5, 1e-9);
  EXPECT_FALSE(k.project(Eigen::Vector3d(0, 0, -1), u, v));
}

TEST(CameraIntrinsics, SaveLoadRoundTrip) {
  const std::string path = gasp::test::scratchDir() + "/k.txt";
  const auto k = CameraIntrinsics::tumFreiburg1();
  k.save(path);
  EXPECT_EQ(CameraIntrinsics::load(path), k);
  EXPECT_EQ(CameraIntrinsics::fromPresetOrFile(path), k);
}

TEST(CameraIntrinsics, MalformedFileNamesFileAndLine) {
  const std::string path = gasp::test::scratchDir() + "/bad.txt";
  std::ofstream(path) << "width: 640\nheight: 480\nfx: abc\n";
  try {
    CameraIntrinsics::load(path);
    FAIL() << "expected an error";
  } catch (const gasp::Error& e) {
    EXPECT_NE(std::string(e.what()).find(path + ":3"), std::string::npos) << e.what();
  }
  std::ofstream(path) << "width: 640\nheight: 480\nfx: 500\nfy: 500\ncx: 320\n";
  EXPECT_THROW(CameraIntrinsics::load(path), gasp::Error);  // cy missing
  std::ofstream(path) << "width: 640\nheight: 480\nfx: -1\nfy: 500\ncx: 320\ncy: 240\n";
  EXPECT_THROW(CameraIntrinsics::load(path), gasp::Error);  // negative focal length
  EXPECT_THROW(CameraIntrinsics::load(path + ".missing"), gasp::Error);
}

TEST(CameraIntrinsics, SizesAreWholePixelsAndKeysAppearOnce) {
  const std::string path = gasp::test::scratchDir() + "/k.txt";
  const auto message = [&](const std::string& text) {
    std::ofstream(path) << text;
    try {
      CameraIntrinsics::load(path);
    } catch (const gasp::Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  const std::string rest = "fx: 500\nfy: 500\ncx: 320\ncy: 240\n";
  EXPECT_NE(message("width: 99999999999\nheight: 480\n" + rest).find(path + ":1: width must be a whole number"),
            std::string::npos);
  EXPECT_NE(message("width: 640.5\nheight: 480\n" + rest).find("whole number"), std::string::npos);
  EXPECT_NE(message("width: 640\nheight: 480\n" + rest + "fx: 400\n").find(path + ":7: key 'fx' appears twice"),
            std::string::npos);
  EXPECT_EQ(message("width: 640\nheight: 480\n" + rest), "");
  // Neither a preset nor a file: the message lists the presets.
  try {
    CameraIntrinsics::fromPresetOrFile("fr9");
    FAIL() << "expected an error";
  } catch (const gasp::Error& e) {
    EXPECT_NE(std::string(e.what()).find("neither a preset (fr1, fr2, fr3, ros)"), std::string::npos) << e.what();
  }
  CameraIntrinsics k;
  k.width = 100000;
  EXPECT_THROW(k.validate(), gasp::Error);
}
