#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "gasp/core/error.h"
#include "gasp/core/tum_dataset.h"
#include "gasp_test_data.h"

TEST(TumDataset, ReadsFr1Desk9WithGroundTruthAndRgb) {
  GASP_REQUIRE_DATA(dir, "tum/fr1_desk9");
  const auto ds = gasp::TumDataset::open(dir);
  ASSERT_EQ(ds.size(), 9u);
  EXPECT_EQ(ds.countWithGroundTruth(), 9u);
  EXPECT_DOUBLE_EQ(ds.intrinsics().fx, 517.3);  // guessed from "fr1_" in the folder name
  // fr1's lens distortion: the images are resampled to the pinhole camera.
  EXPECT_TRUE(ds.undistorts());
  EXPECT_FALSE(gasp::hasLensDistortion(ds.intrinsics()));
  EXPECT_TRUE(gasp::hasLensDistortion(ds.calibratedIntrinsics()));
  for (std::size_t i = 0; i < ds.size(); ++i) {
    EXPECT_TRUE(ds.frame(i).rgb_path.has_value());
    if (i > 0) {
      EXPECT_GT(ds.frame(i).timestamp, ds.frame(i - 1).timestamp);
    }
  }
  const cv::Mat depth = ds.loadDepth(0);
  EXPECT_EQ(depth.type(), CV_32FC1);
  EXPECT_EQ(depth.cols, 640);
  EXPECT_GT(gasp::countValidDepth(depth), 200000u);
  EXPECT_EQ(ds.loadRgb(0).type(), CV_8UC3);
  // Consecutive frames: ~14 mm apart per the data's README.
  const auto T_0_1 = gasp::relativePose(*ds.frame(0).T_world_camera, *ds.frame(1).T_world_camera);
  EXPECT_LT(T_0_1.translation().norm(), 0.05);
  EXPECT_THROW(ds.frame(9), gasp::Error);
  // Ground truth at an offset: offset 0 is the frame's own; 30 ms earlier is another mocap sample
  // (100 Hz), close by; far outside the trajectory there is none.
  EXPECT_TRUE(ds.groundTruthOf(2)->isApprox(*ds.frame(2).T_world_camera));
  const auto earlier = ds.groundTruthOf(2, -0.03);
  ASSERT_TRUE(earlier.has_value());
  EXPECT_FALSE(earlier->isApprox(*ds.frame(2).T_world_camera));
  EXPECT_LT(gasp::relativePose(*earlier, *ds.frame(2).T_world_camera).translation().norm(), 0.05);
  EXPECT_FALSE(ds.groundTruthOf(2, -1e6).has_value());
}

TEST(TumDataset, ReadsFr3CabinetKeyframes) {
  GASP_REQUIRE_DATA(dir, "tum/fr3_cabinet_kf");
  const auto ds = gasp::TumDataset::open(dir);
  ASSERT_EQ(ds.size(), 30u);
  EXPECT_EQ(ds.countWithGroundTruth(), 30u);
  EXPECT_DOUBLE_EQ(ds.intrinsics().fx, 535.4);
  EXPECT_FALSE(ds.undistorts());  // fr3 has no lens distortion
  EXPECT_EQ(ds.loadRgb(3).type(), CV_8UC3);  // JPEG rgb
  const cv::Mat d = ds.loadDepth(29);
  EXPECT_GT(gasp::countValidDepth(d), 100000u);
}

TEST(TumDataset, ExplicitIntrinsicsOverrideAndGroundTruthWindow) {
  GASP_REQUIRE_DATA(dir, "tum/fr1_desk9");
  gasp::TumDataset::Options opt;
  opt.intrinsics = gasp::CameraIntrinsics::rosDefault();
  opt.max_dt = 1e-6;  // ground truth at 100 Hz: almost no frame has a pose this close
  const auto ds = gasp::TumDataset::open(dir, opt);
  EXPECT_EQ(ds.intrinsicsSource(), "option");
  EXPECT_LT(ds.countWithGroundTruth(), 9u);
}

TEST(TumDataset, UndistortionCanBeTurnedOff) {
  GASP_REQUIRE_DATA(dir, "tum/fr1_desk9");
  gasp::TumDataset::Options opt;
  opt.undistort = false;
  const auto raw = gasp::TumDataset::open(dir, opt);
  const auto undistorted = gasp::TumDataset::open(dir);
  EXPECT_FALSE(raw.undistorts());
  EXPECT_FALSE(gasp::hasLensDistortion(raw.intrinsics()));  // ignored, as documented
  const cv::Mat a = raw.loadDepthRaw(0), b = undistorted.loadDepthRaw(0);
  ASSERT_EQ(a.type(), CV_16UC1);
  ASSERT_EQ(b.type(), CV_16UC1);
  EXPECT_GT(cv::norm(a, b, cv::NORM_L1), 0.0);  // resampled
  // The centre moves little (distortion grows with the radius); the corners move by pixels.
  const cv::Rect centre(300, 220, 40, 40);
  EXPECT_GT(cv::countNonZero(a(centre) == b(centre)), 1000);
  const cv::Mat rgb_raw = raw.loadRgb(0), rgb = undistorted.loadRgb(0);
  ASSERT_EQ(rgb_raw.size(), rgb.size());
  EXPECT_GT(cv::norm(rgb_raw(cv::Rect(0, 0, 80, 80)), rgb(cv::Rect(0, 0, 80, 80)), cv::NORM_L1), 0.0);  // resampled too
}

TEST(TumDataset, MissingAndMalformedInputs) {
  const std::string dir = gasp::test::scratchDir();
  EXPECT_THROW(gasp::TumDataset::open(dir + "/nope"), gasp::Error);
  EXPECT_THROW(gasp::TumDataset::open(dir), gasp::Error);  // no depth.txt
  std::ofstream(dir + "/depth.txt") << "# c\n1.0 depth/1.png\n2.0\n";
  try {
    gasp::TumDataset::open(dir);
    FAIL();
  } catch (const gasp::Error& e) {
    EXPECT_NE(std::string(e.what()).find("depth.txt:3"), std::string::npos) << e.what();
  }
  // A repeated or earlier timestamp would pair the wrong ground truth: an error naming the line.
  for (const char* list : {"1.0 depth/1.png\n1.0 depth/2.png\n", "2.0 depth/1.png\n1.0 depth/2.png\n"}) {
    std::ofstream(dir + "/depth.txt") << list;
    try {
      gasp::TumDataset::open(dir);
      FAIL() << list;
    } catch (const gasp::Error& e) {
      EXPECT_NE(std::string(e.what()).find("depth.txt:2: timestamp 1.0 is not after"), std::string::npos) << e.what();
    }
  }
  std::ofstream(dir + "/depth.txt") << "1.0 depth/1.png\n";
  const auto ds = gasp::TumDataset::open(dir);
  EXPECT_EQ(ds.size(), 1u);
  EXPECT_THROW(ds.loadDepth(0), gasp::Error);  // the PNG is missing
}

TEST(TumDataset, SaysWhereItsIntrinsicsCameFromAndWarnsOfTheDefaultGuess) {
  // A folder of a user's own camera: no intrinsics.txt and no TUM camera in its name.
  const std::string dir = gasp::test::scratchDir() + "/my_robot";
  std::filesystem::create_directories(dir);
  std::ofstream(dir + "/depth.txt") << "1.0 depth/1.png\n";
  const auto guessed = gasp::TumDataset::open(dir);
  EXPECT_TRUE(guessed.intrinsicsAreTheDefaultGuess());
  EXPECT_EQ(guessed.intrinsicsSummary(), "fx 525 fy 525 cx 319.5 cy 239.5 (640x480, preset ros (default; pass intrinsics to override))");
  EXPECT_NE(guessed.intrinsicsWarning().find("ROS default intrinsics"), std::string::npos) << guessed.intrinsicsWarning();
  EXPECT_NE(guessed.intrinsicsWarning().find(dir + "/intrinsics.txt"), std::string::npos) << guessed.intrinsicsWarning();
  // Given, or found in the folder: no warning, and the summary names the source.
  gasp::TumDataset::Options opt;
  opt.intrinsics = gasp::CameraIntrinsics::tumFreiburg3();
  const auto given = gasp::TumDataset::open(dir, opt);
  EXPECT_FALSE(given.intrinsicsAreTheDefaultGuess());
  EXPECT_TRUE(given.intrinsicsWarning().empty());
  EXPECT_EQ(given.intrinsicsSummary(), "fx 535.4 fy 539.2 cx 320.1 cy 247.6 (640x480, option)");
  gasp::CameraIntrinsics::tumFreiburg3().save(dir + "/intrinsics.txt");
  const auto found = gasp::TumDataset::open(dir);
  EXPECT_FALSE(found.intrinsicsAreTheDefaultGuess());
  EXPECT_TRUE(found.intrinsicsWarning().empty());
  EXPECT_NE(found.intrinsicsSummary().find("intrinsics.txt"), std::string::npos) << found.intrinsicsSummary();
}

TEST(TumDataset, SummaryOfAnUndistortedFolder) {
  GASP_REQUIRE_DATA(dir, "tum/fr1_desk9");
  const auto ds = gasp::TumDataset::open(dir);
  EXPECT_EQ(ds.intrinsicsSummary(), "fx 517.3 fy 516.5 cx 318.6 cy 255.3 (640x480, preset fr1 (from the folder name), undistorted)");
  EXPECT_TRUE(ds.intrinsicsWarning().empty());
}
