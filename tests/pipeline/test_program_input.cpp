// Bad files and option values given to the image programs (gasp-associate, gasp-segment,
// gasp-pairs-plot): a usage error or an error naming the file, never an OpenCV exception that
// aborts the program. No real data needed.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "gasp/core/depth_image.h"
#include "gasp_test_data.h"
#include "program_run.h"

namespace {

using gasp::test::contains;
using gasp::test::runProgram;

/// A 640 x 480 depth PNG of a tilted plane and a box on it (enough structure to segment).
std::string depthPng(const std::string& path) {
  cv::Mat depth(480, 640, CV_32FC1);
  for (int v = 0; v < 480; ++v)
    for (int u = 0; u < 640; ++u)
      depth.at<float>(v, u) = 1.5f + 0.002f * static_cast<float>(u) - (u > 250 && u < 400 && v > 150 && v < 300 ? 0.3f : 0.0f);
  gasp::saveDepth(path, depth, gasp::kTumDepthUnitsPerMetre);
  return path;
}

std::uint32_t crc32(const std::string& bytes) {
  std::uint32_t c = 0xFFFFFFFFu;
  for (const unsigned char b : bytes) {
    c ^= b;
    for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1u)));
  }
  return ~c;
}

/// A valid PNG whose header claims width x height pixels (OpenCV refuses to allocate them).
std::string pngClaiming(const std::string& path, std::uint32_t width, std::uint32_t height) {
  std::string png = std::string("\x89PNG\r\n\x1a\n", 8);
  const auto be32 = [](std::uint32_t v) {
    return std::string{static_cast<char>(v >> 24), static_cast<char>(v >> 16), static_cast<char>(v >> 8),
                       static_cast<char>(v)};
  };
  const std::string ihdr = "IHDR" + be32(width) + be32(height) + std::string("\x10\x00\x00\x00\x00", 5);  // 16-bit grey
  png += be32(13) + ihdr + be32(crc32(ihdr));
  png += be32(0) + "IEND" + be32(crc32("IEND"));
  std::ofstream(path, std::ios::binary) << png;
  return path;
}

}  // namespace

TEST(ImagePrograms, AnOutputNameWithoutImageFormatIsAUsageError) {
  const std::string dir = gasp::test::scratchDir();
  const std::string a = depthPng(dir + "/a.png");
  auto run = runProgram("gasp-associate", "--depth-a " + a + " --depth-b " + a + " --out " + dir + "/pic.txt");
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_TRUE(contains(run.output, "pic.txt': no image format")) << run.output;
  run = runProgram("gasp-segment", "--depth " + a + " --out " + dir + "/seg");
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_TRUE(contains(run.output, "no image format")) << run.output;
  // --pairs needs --tum (it wrote a picture to an empty name before).
  run = runProgram("gasp-segment", "--depth " + a + " --pairs 1");
  EXPECT_EQ(run.exit_code, 2) << run.output;
  // An output folder that is a file.
  std::ofstream(dir + "/depth.txt") << "1.0 a.png\n";
  run = runProgram("gasp-segment", "--tum " + dir + " --intrinsics ros --out " + a);
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_TRUE(contains(run.output, "cannot create the output folder")) << run.output;
  // Empty depth.txt: no frames is an error, not an empty success.
  std::filesystem::create_directories(dir + "/empty");
  std::ofstream(dir + "/empty/depth.txt") << "# nothing\n";
  run = runProgram("gasp-segment", "--tum " + dir + "/empty --intrinsics ros --out " + dir + "/out");
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_TRUE(contains(run.output, "no frames")) << run.output;
  // The good case still works.
  run = runProgram("gasp-segment", "--depth " + a + " --out " + dir + "/seg.png --area-cm2 40");
  EXPECT_EQ(run.exit_code, 0) << run.output;
  run = runProgram("gasp-segment", "--depth " + a + " --out " + dir + "/seg.png --area-cm2 0");
  EXPECT_EQ(run.exit_code, 2) << run.output;
  // Association parameters out of their range are errors naming the key, before the work.
  for (const char* key : {"lambda: nan", "lambda: 2", "candidates: 0", "neighbourhood_k: -1", "r_dev_m: -1",
                          "theta_dev_rad: -5", "distinctiveness_ratio: 0", "distinctiveness_ratio: 1.5"}) {
    const std::string params = dir + "/bad_params.yaml";
    std::ofstream(params) << "associate:\n  " << key << "\n";
    run = runProgram("gasp-associate", "--depth-a " + a + " --depth-b " + a + " --out " + dir + "/p.png --params " + params);
    EXPECT_EQ(run.exit_code, 1) << key << '\n' << run.output;
    const std::string name = std::string(key).substr(0, std::string(key).find(':'));
    EXPECT_TRUE(contains(run.output, "associate." + name)) << key << '\n' << run.output;
    EXPECT_FALSE(contains(run.output, "patches_a")) << key << '\n' << run.output;
  }
}

TEST(ImagePrograms, AnImageClaimingBillionsOfPixelsIsAnErrorNamingTheFile) {
  const std::string dir = gasp::test::scratchDir();
  const std::string huge = pngClaiming(dir + "/huge.png", 100000, 100000);
  const std::string a = depthPng(dir + "/a.png");
  auto run = runProgram("gasp-associate", "--depth-a " + huge + " --depth-b " + a + " --out " + dir + "/p.png");
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_TRUE(contains(run.output, "huge.png' is not a readable image")) << run.output;
  run = runProgram("gasp-segment", "--depth " + huge + " --out " + dir + "/s.png");
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_TRUE(contains(run.output, "huge.png' is not a readable image")) << run.output;
}

TEST(ImagePrograms, PairsPlotRefusesBadTablesAndSkipsMissingErrors) {
  const std::string dir = gasp::test::scratchDir();
  const std::string header = "skip,method,pairs,failed,rmse_t_m,rmse_r_deg,fail_pct,within_5cm_2deg_pct,median_ms\n";
  std::ofstream(dir + "/only_header.csv") << header;
  auto run = runProgram("gasp-pairs-plot", "--csv " + dir + "/only_header.csv --out " + dir + "/f.png");
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_TRUE(contains(run.output, "no rows")) << run.output;
  std::ofstream(dir + "/nan.csv") << header << "10,gasp,5,0,nan,1.0,0.0,100.0,50.0\n";
  run = runProgram("gasp-pairs-plot", "--csv " + dir + "/nan.csv --out " + dir + "/f.png");
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_TRUE(contains(run.output, "nan.csv:2: 'nan' is not finite")) << run.output;
  // A skip where every pair failed has no RMSE (empty cells): plotted without a point.
  std::ofstream(dir + "/failed.csv") << header << "10,gasp,5,0,0.01,1.0,0.0,100.0,50.0\n20,gasp,5,5,,,100.0,0.0,60.0\n";
  run = runProgram("gasp-pairs-plot", "--csv " + dir + "/failed.csv --out " + dir + "/f.png");
  EXPECT_EQ(run.exit_code, 0) << run.output;
  EXPECT_TRUE(std::filesystem::exists(dir + "/f.png"));
  run = runProgram("gasp-pairs-plot", "--csv " + dir + "/failed.csv --out " + dir + "/f.txt");
  EXPECT_EQ(run.exit_code, 2) << run.output;
  // A negative skip (std::stoul would wrap it round to 18446744073709551606), skip 0, and two rows
  // for one skip and method (two tables joined) are refused, naming the line.
  for (const auto& [rows, message] : std::vector<std::pair<std::string, std::string>>{
           {"-10,gasp,5,0,0.01,1.0,0.0,100.0,50.0\n", "bad.csv:2: '-10' is not a skip"},
           {"0,gasp,5,0,0.01,1.0,0.0,100.0,50.0\n", "bad.csv:2: '0' is not a skip"},
           {"10,gasp,5,0,0.01,1.0,0.0,100.0,50.0\n10,gasp,5,0,0.02,1.0,0.0,100.0,50.0\n",
            "bad.csv:3: a second row for skip 10 and method gasp"}}) {
    std::ofstream(dir + "/bad.csv") << header << rows;
    run = runProgram("gasp-pairs-plot", "--csv " + dir + "/bad.csv --out " + dir + "/f.png");
    EXPECT_EQ(run.exit_code, 1) << rows << run.output;
    EXPECT_TRUE(contains(run.output, message)) << rows << run.output;
  }
}
