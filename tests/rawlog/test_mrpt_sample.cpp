// Reading MRPT's own RGB-D sample (mrpt-common: /usr/share/mrpt/datasets/tests_rgbd.rawlog).
#include <gtest/gtest.h>

#include <filesystem>

#include "gasp/core/depth_image.h"
#include "gasp/rawlog/rawlog_reader.h"

TEST(MrptSample, ReadsTestsRgbdRawlog) {
  const std::string path = "/usr/share/mrpt/datasets/tests_rgbd.rawlog";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " not found (package mrpt-common)";
  gasp::RawlogReader reader(path);
  const auto f = reader.next();
  ASSERT_TRUE(f.has_value());
  EXPECT_FALSE(reader.next().has_value());
  EXPECT_EQ(reader.format(), gasp::RawlogFormat::Observations);
  EXPECT_EQ(f->sensor_label, "OPENNI2");
  ASSERT_EQ(f->depth_m.cols, 640);
  ASSERT_EQ(f->depth_m.rows, 480);
  EXPECT_EQ(f->depth_m.type(), CV_32FC1);
  EXPECT_DOUBLE_EQ(f->depth_units_per_metre, 1000.0);  // rangeUnits 0.001
  // Plausible indoor depth: most pixels valid, between 0.3 m and 10 m.
  const std::size_t valid = gasp::countValidDepth(f->depth_m);
  EXPECT_GT(valid, 640u * 480u / 2);
  double lo = 0.0, hi = 0.0;
  cv::minMaxLoc(f->depth_m, &lo, &hi, nullptr, nullptr, f->depth_m > 0);
  EXPECT_GT(lo, 0.3);
  EXPECT_LT(hi, 10.0);
  // Depth and intensity cameras with different intrinsics; colour image of the same size.
  EXPECT_NE(f->depth_intrinsics, f->rgb_intrinsics);
  EXPECT_EQ(f->depth_intrinsics.width, 640);
  EXPECT_EQ(f->rgb.type(), CV_8UC3);
  EXPECT_EQ(f->rgb.cols, 640);
  EXPECT_NEAR(f->timestamp, 1462879443.617188, 1e-5);
  std::cout << "tests_rgbd: depth K fx " << f->depth_intrinsics.fx << " cx " << f->depth_intrinsics.cx
            << ", rgb K fx " << f->rgb_intrinsics.fx << " cx " << f->rgb_intrinsics.cx
            << ", depth range " << lo << ".." << hi << " m, valid " << valid
            << ", T_depth_rgb t = " << f->T_depth_rgb.translation().transpose() << "\n";
}
