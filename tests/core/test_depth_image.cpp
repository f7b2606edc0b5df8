#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <string>

#include "gasp/core/depth_image.h"
#include "gasp/core/error.h"
#include "gasp/core/image_file.h"
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

// Crash inputs of fuzz/fuzz_depth_png (docs/experiments/2026-11-28-fuzzing.md), in tests/core/data:
// files named .png holding a JPEG (OpenCV reads by content) whose frame header declares 13568 x
// 64255 pixels in 53 bytes (cv::imread allocated 2.6 GB before decoding: libFuzzer's malloc limit)
// or 21059 x 21321 in 318 bytes (1.3 GB, seconds per read). The header is now checked against what
// the file can hold (image_header.h): an error naming the file, before any allocation. Likewise a
// PNG whose IHDR declares 60000 x 60000 16-bit pixels in a file of 57 bytes.
TEST(DepthImage, HeadersDeclaringMoreThanTheFileHoldsAreErrors) {
  const std::filesystem::path data = std::filesystem::path(__FILE__).parent_path() / "data";
  const std::string dir = gasp::test::scratchDir();
  const auto message = [](const std::function<void()>& read) -> std::string {
    try {
      read();
    } catch (const gasp::Error& e) {
      return e.what();
    }
    return "";
  };
  const std::string jpeg = (data / "jpeg_header_13568x64255.png").string();
  const std::string expected = "is not a readable image: the JPEG header declares 13568 x 64255 pixels, more than a "
                               "file of 53 bytes can hold";
  EXPECT_NE(message([&] { gasp::loadDepthRaw(jpeg); }).find("depth image '" + jpeg + "' " + expected), std::string::npos)
      << message([&] { gasp::loadDepthRaw(jpeg); });
  EXPECT_NE(message([&] { gasp::readImage(jpeg, cv::IMREAD_COLOR, "rgb image"); }).find("rgb image '" + jpeg + "' " + expected),
            std::string::npos);
  const std::string slow = (data / "jpeg_header_21059x21321.png").string();
  EXPECT_NE(message([&] { gasp::loadDepthRaw(slow); }).find("declares 21059 x 21321 pixels, more than a file of 318 bytes"),
            std::string::npos)
      << message([&] { gasp::loadDepthRaw(slow); });

  // A PNG signature and an IHDR of 60000 x 60000, 16-bit grey, then nothing.
  const std::string png = dir + "/huge_header.png";
  {
    const unsigned char bytes[] = {0x89, 'P', 'N', 'G', 0x0d, 0x0a, 0x1a, 0x0a, 0, 0, 0, 13, 'I', 'H', 'D', 'R',
                                   0, 0, 0xea, 0x60, 0, 0, 0xea, 0x60, 16, 0, 0, 0, 0, 0x12, 0x34, 0x56, 0x78,
                                   0, 0, 0, 0, 'I', 'E', 'N', 'D', 0xae, 0x42, 0x60, 0x82, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
    std::ofstream(png, std::ios::binary).write(reinterpret_cast<const char*>(bytes), sizeof bytes);
  }
  EXPECT_NE(message([&] { gasp::loadDepthRaw(png); })
                .find("the PNG header declares 60000 x 60000 pixels, more than a file of 57 bytes can hold"),
            std::string::npos)
      << message([&] { gasp::loadDepthRaw(png); });
  // Real images still read (a 640 x 480 PNG of 16-bit depth compresses far less than 1032:1).
  const std::string real = dir + "/real.png";
  cv::imwrite(real, cv::Mat(480, 640, CV_16UC1, cv::Scalar(1000)));
  EXPECT_NO_THROW(gasp::loadDepthRaw(real, 640, 480));
}
