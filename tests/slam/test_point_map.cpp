// VoxelPointMap (point_map.h): points at their poses, one per voxel, and its PLY file.
#include <gtest/gtest.h>

#include <fstream>
#include <limits>
#include <string>

#include "gasp/core/error.h"
#include "gasp/slam/point_map.h"
#include "gasp_test_data.h"

namespace {

gasp::CameraIntrinsics smallCamera() {
  gasp::CameraIntrinsics k;
  k.width = 40, k.height = 30, k.fx = k.fy = 40, k.cx = 19.5, k.cy = 14.5;
  return k;
}

}  // namespace

TEST(VoxelPointMap, AWallSeenTwiceFromPosesIsOneSetOfPointsInTheWorld) {
  const auto k = smallCamera();
  const cv::Mat wall(k.height, k.width, CV_32FC1, cv::Scalar(2.0));  // a plane 2 m ahead
  gasp::VoxelPointMap map(0.05, 4.0);
  gasp::Isometry3 T = gasp::Isometry3::Identity();
  T.translation() = Eigen::Vector3d(0, 0, -1);  // one metre back: the wall is at world z = 1
  map.insert(wall, k, T);
  const std::size_t once = map.size();
  EXPECT_GT(once, 100u);
  map.insert(wall, k, T);  // the same view again adds no voxel
  EXPECT_EQ(map.size(), once);
  for (const auto& p : map.points()) EXPECT_NEAR(p.z(), 1.0, 0.026);
  // Beyond the maximum depth: nothing.
  gasp::VoxelPointMap near_only(0.05, 1.5);
  near_only.insert(wall, k, T);
  EXPECT_EQ(near_only.size(), 0u);
  // NaN and zero depth are no data.
  cv::Mat holes = wall.clone();
  holes.setTo(0.0f);
  holes.at<float>(3, 4) = std::nanf("");
  gasp::VoxelPointMap empty(0.05);
  empty.insert(holes, k, T);
  EXPECT_EQ(empty.size(), 0u);

  const std::string path = gasp::test::scratchDir() + "/map.ply";
  map.writePly(path);
  std::ifstream in(path);
  std::string line;
  std::size_t vertices = 0, lines = 0;
  bool header = true;
  while (std::getline(in, line)) {
    if (header && line.rfind("element vertex ", 0) == 0) vertices = std::stoul(line.substr(15));
    if (!header) ++lines;
    if (line == "end_header") header = false;
  }
  EXPECT_EQ(vertices, once);
  EXPECT_EQ(lines, once);
}

TEST(VoxelPointMap, BadInputIsAnError) {
  const auto k = smallCamera();
  EXPECT_THROW(gasp::VoxelPointMap(0.0), gasp::Error);
  EXPECT_THROW(gasp::VoxelPointMap(std::nan("")), gasp::Error);
  // Below 1 mm the +-2^20-voxel grid would silently drop everything beyond a metre; above 10 m
  // a voxel is no map.
  EXPECT_THROW(gasp::VoxelPointMap(1e-6), gasp::Error);
  EXPECT_THROW(gasp::VoxelPointMap(1e300), gasp::Error);
  EXPECT_THROW(gasp::VoxelPointMap(0.01, std::numeric_limits<double>::infinity()), gasp::Error);
  {
    // A point beyond the grid is counted, not silently lost.
    gasp::VoxelPointMap tiny(0.001);
    gasp::CameraIntrinsics kk;
    gasp::Isometry3 far = gasp::Isometry3::Identity();
    far.translation().x() = 5000.0;  // 5 km: beyond +-1048 m at 1 mm
    tiny.insert(cv::Mat(kk.height, kk.width, CV_32FC1, cv::Scalar(1.0)), kk, far);
    EXPECT_EQ(tiny.size(), 0u);
    EXPECT_EQ(tiny.pointsOutside(), static_cast<std::size_t>(kk.width * kk.height));
  }
  gasp::VoxelPointMap map;
  EXPECT_THROW(map.insert(cv::Mat(10, 10, CV_32FC1, cv::Scalar(1.0)), k, gasp::Isometry3::Identity()), gasp::Error);
  gasp::Isometry3 bad = gasp::Isometry3::Identity();
  bad.translation().x() = INFINITY;
  EXPECT_THROW(map.insert(cv::Mat(k.height, k.width, CV_32FC1, cv::Scalar(1.0)), k, bad), gasp::Error);
  EXPECT_THROW(map.writePly("/nonexistent-dir/x.ply"), gasp::Error);
}
