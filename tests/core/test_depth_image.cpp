#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include <fstream>
#include <limits>

#include "gasp/core/depth_image.h"
#include "gasp/core/error.h"
#include "gasp_test_data.h"

TEST(DepthImage, RawToMetresAndBackIsExact) {
  cv::Mat raw(4, 5, CV_16UC1);
  for (int i = 0; i < 20; ++i) raw.at<std::uint16_t>(i / 5, i % 5) = static_cast<std::uint16_t>(i * 3001);
  const cv::Mat d = gasp::depthFromRaw(raw, 5000.0);
  EXPECT_FLOAT_EQ(d.at<float>(0, 1), 3001.0f / 5000.0f);
  EXPECT_EQ(d.at<float>(0, 0), 0.0f);  // 0 = no data
  const cv::Mat back = gasp::depthToRaw(d, 5000.0);
  EXPECT_EQ(cv::countNonZero(back != raw), 0);
}

TEST(DepthImage, InvalidValuesBecomeZero) {
  cv::Mat d(1, 4, CV_32FC1);
  d.at<float>(0, 0) = std::numeric_limits<float>::quiet_NaN();
  d.at<float>(0, 1) = -1.0f;
  d.at<float>(0, 2) = 20.0f;  // 100000 units: beyond uint16
  d.at<float>(0, 3) = 1.23456f;
  const cv::Mat raw = gasp::depthToRaw(d, 5000.0);
  EXPECT_EQ(raw.at<std::uint16_t>(0, 0), 0);
  EXPECT_EQ(raw.at<std::uint16_t>(0, 1), 0);
  EXPECT_EQ(raw.at<std::uint16_t>(0, 2), 0);
  EXPECT_EQ(raw.at<std::uint16_t>(0, 3), 6173);
  EXPECT_EQ(gasp::countValidDepth(d), 2u);
}

TEST(DepthImage, PngRoundTrip) {
  const std::string path = gasp::test::scratchDir() + "/d.png";
  cv::Mat d(48, 64, CV_32FC1, cv::Scalar(1.5f));
  d.at<float>(3, 7) = 0.0f;
  gasp::saveDepth(path, d);
  const cv::Mat back = gasp::loadDepth(path, 5000.0, 64, 48);
  EXPECT_EQ(cv::countNonZero(back != d), 0);
}

TEST(DepthImage, BadFilesGiveClearErrors) {
  const std::string dir = gasp::test::scratchDir();
  EXPECT_THROW(gasp::loadDepthRaw(dir + "/missing.png"), gasp::Error);
  cv::imwrite(dir + "/eight_bit.png", cv::Mat(10, 10, CV_8UC1, cv::Scalar(7)));
  try {
    gasp::loadDepthRaw(dir + "/eight_bit.png");
    FAIL() << "8-bit depth accepted";
  } catch (const gasp::Error& e) {
    EXPECT_NE(std::string(e.what()).find("16-bit"), std::string::npos) << e.what();
  }
  cv::imwrite(dir + "/small.png", cv::Mat(10, 10, CV_16UC1, cv::Scalar(7)));
  EXPECT_NO_THROW(gasp::loadDepthRaw(dir + "/small.png"));
  EXPECT_THROW(gasp::loadDepthRaw(dir + "/small.png", 640, 480), gasp::Error);
  std::ofstream(dir + "/garbage.png") << "not a png";
  EXPECT_THROW(gasp::loadDepthRaw(dir + "/garbage.png"), gasp::Error);
  EXPECT_THROW(gasp::depthFromRaw(cv::Mat(2, 2, CV_8UC1)), gasp::Error);
  EXPECT_THROW(gasp::depthFromRaw(cv::Mat(2, 2, CV_16UC1), 0.0), gasp::Error);
}
