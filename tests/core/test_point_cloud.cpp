#include <gtest/gtest.h>

#include <limits>

#include "gasp/core/error.h"
#include "gasp/core/point_cloud.h"

TEST(PointCloud, BackProjectionFollowsPinholeModel) {
  gasp::CameraIntrinsics k;
  k.width = 8; k.height = 6; k.fx = 10; k.fy = 20; k.cx = 3.5; k.cy = 2.5;
  cv::Mat d(6, 8, CV_32FC1, cv::Scalar(2.0f));
  d.at<float>(1, 2) = 0.0f;
  d.at<float>(4, 6) = std::numeric_limits<float>::quiet_NaN();
  const auto cloud = gasp::backProject(d, k);
  ASSERT_EQ(cloud.points.size(), 48u);
  EXPECT_EQ(cloud.countValid(), 46u);
  EXPECT_FALSE(cloud.isValid(2, 1));
  EXPECT_FALSE(cloud.isValid(6, 4));
  const Eigen::Vector3f p = cloud.at(7, 5);
  EXPECT_FLOAT_EQ(p.x(), (7 - 3.5f) * 2.0f / 10.0f);
  EXPECT_FLOAT_EQ(p.y(), (5 - 2.5f) * 2.0f / 20.0f);
  EXPECT_FLOAT_EQ(p.z(), 2.0f);
}

TEST(PointCloud, WrongSizeOrTypeThrows) {
  gasp::CameraIntrinsics k;  // 640x480
  EXPECT_THROW(gasp::backProject(cv::Mat(10, 10, CV_32FC1, cv::Scalar(1.0f)), k), gasp::Error);
  EXPECT_THROW(gasp::backProject(cv::Mat(480, 640, CV_16UC1), k), gasp::Error);
  const auto empty = gasp::backProject(cv::Mat(480, 640, CV_32FC1, cv::Scalar(0.0f)), k);
  EXPECT_EQ(empty.countValid(), 0u);
}
