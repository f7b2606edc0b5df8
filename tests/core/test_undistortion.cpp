// Lens undistortion of depth and colour images (undistortion.h).
#include <gtest/gtest.h>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include <cmath>
#include <limits>

#include "gasp/core/error.h"
#include "gasp/core/point_cloud.h"
#include "gasp/core/undistortion.h"

namespace {

/// Depth [m] of the plane n.x = d seen by a camera with distortion k: each (distorted) pixel's
/// ray is found with cv::undistortPoints, then intersected with the plane.
cv::Mat distortedPlaneDepth(const gasp::CameraIntrinsics& k, const Eigen::Vector3d& n, double d) {
  std::vector<cv::Point2f> pixels;
  for (int v = 0; v < k.height; ++v)
    for (int u = 0; u < k.width; ++u) pixels.emplace_back(static_cast<float>(u), static_cast<float>(v));
  std::vector<cv::Point2f> rays;
  const cv::Matx33d K(k.fx, 0, k.cx, 0, k.fy, k.cy, 0, 0, 1);
  cv::undistortPoints(pixels, rays, K, cv::Mat(1, 5, CV_64F, const_cast<double*>(k.distortion.data())));
  cv::Mat depth(k.height, k.width, CV_32FC1);
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const Eigen::Vector3d ray(rays[i].x, rays[i].y, 1.0);
    depth.at<float>(static_cast<int>(i) / k.width, static_cast<int>(i) % k.width) = static_cast<float>(d / n.dot(ray));
  }
  return depth;
}

/// RMS distance [m] of the back-projected valid pixels (pinhole model) to the plane n.x = d.
double planeRms(const cv::Mat& depth, const gasp::CameraIntrinsics& k, const Eigen::Vector3d& n, double d) {
  const auto cloud = gasp::backProject(depth, k);
  double sum = 0.0;
  int count = 0;
  for (const auto& p : cloud.points) {
    if (!p.allFinite()) continue;
    const double e = n.dot(p.cast<double>()) - d;
    sum += e * e;
    ++count;
  }
  return count > 0 ? std::sqrt(sum / count) : std::numeric_limits<double>::infinity();
}

}  // namespace

TEST(Undistortion, NoDistortionIsTheIdentity) {
  const auto k = gasp::CameraIntrinsics::tumFreiburg3();
  const gasp::Undistortion u(k);
  EXPECT_FALSE(u.active());
  EXPECT_FALSE(gasp::hasLensDistortion(k));
  cv::Mat depth(k.height, k.width, CV_32FC1, cv::Scalar(1.5f));
  const cv::Mat out = u.applyToDepth(depth);
  EXPECT_EQ(out.data, depth.data);
  EXPECT_EQ(u.pinhole(), k);
}

TEST(Undistortion, Fr1DistortedPlaneBecomesPlanarUnderThePinholeModel) {
  // A tilted plane 1-2 m away seen through fr1's lens: back-projected with the pinhole model as
  // stored it bends (RMS 4 mm, centimetres at the corners); resampled, it is flat within the
  // nearest-neighbour resampling error (0.3 mm).
  const auto k = gasp::CameraIntrinsics::tumFreiburg1();
  ASSERT_TRUE(gasp::hasLensDistortion(k));
  const Eigen::Vector3d n = Eigen::Vector3d(0.3, -0.2, 1.0).normalized();
  const double d = 1.4;
  const cv::Mat distorted = distortedPlaneDepth(k, n, d);
  const gasp::Undistortion u(k);
  ASSERT_TRUE(u.active());
  for (double c : u.pinhole().distortion) EXPECT_EQ(c, 0.0);
  EXPECT_EQ(u.pinhole().fx, k.fx);
  const cv::Mat undistorted = u.applyToDepth(distorted);
  ASSERT_EQ(undistorted.type(), CV_32FC1);
  const double rms_raw = planeRms(distorted, u.pinhole(), n, d);
  const double rms_undistorted = planeRms(undistorted, u.pinhole(), n, d);
  std::printf("plane RMS: as stored %.4f m, undistorted %.4f m\n", rms_raw, rms_undistorted);
  EXPECT_GT(rms_raw, 0.003);
  EXPECT_LT(rms_undistorted, 0.001);
  EXPECT_LT(rms_undistorted, 0.2 * rms_raw);
  // Most of the image stays covered (the borders map outside the distorted image).
  EXPECT_GT(cv::countNonZero(undistorted), static_cast<int>(0.9 * undistorted.total()));
}

TEST(Undistortion, NearestNeighbourKeepsDepthValuesAndRawUnits) {
  // Two depths only (a step): nearest neighbour never creates a value in between.
  const auto k = gasp::CameraIntrinsics::tumFreiburg1();
  cv::Mat raw(k.height, k.width, CV_16UC1, cv::Scalar(5000));
  raw(cv::Rect(0, 0, k.width / 2, k.height)).setTo(10000);
  const cv::Mat out = gasp::Undistortion(k).applyToDepth(raw);
  ASSERT_EQ(out.type(), CV_16UC1);
  for (auto it = out.begin<std::uint16_t>(); it != out.end<std::uint16_t>(); ++it)
    ASSERT_TRUE(*it == 0 || *it == 5000 || *it == 10000) << *it;
  // Colour: same size and type, and moved like the depth: a marker near a corner, drawn in both,
  // lands on the same pixels (a registered RGB-D pair stays registered).
  cv::Mat bgr(k.height, k.width, CV_8UC3, cv::Scalar(10, 20, 30));
  cv::Mat marked(k.height, k.width, CV_16UC1, cv::Scalar(5000));
  const cv::Rect marker(40, 40, 30, 30);
  bgr(marker).setTo(cv::Scalar(0, 0, 255));
  marked(marker).setTo(7000);
  const gasp::Undistortion u(k);
  const cv::Mat col = u.applyToImage(bgr), dep = u.applyToDepth(marked);
  EXPECT_EQ(col.type(), CV_8UC3);
  cv::Mat red, near;
  cv::inRange(col, cv::Scalar(0, 0, 200), cv::Scalar(60, 60, 255), red);
  near = dep == 7000;
  const cv::Rect red_box = cv::boundingRect(red), depth_box = cv::boundingRect(near);
  EXPECT_NE(depth_box, marker);  // the lens moved it (pixels near a corner move most)
  EXPECT_LE(std::abs(red_box.x - depth_box.x), 1);
  EXPECT_LE(std::abs(red_box.y - depth_box.y), 1);
  EXPECT_LE(std::abs(red_box.width - depth_box.width), 2);
  EXPECT_TRUE(u.applyToImage(cv::Mat()).empty());
}

TEST(Undistortion, BadInput) {
  const auto k = gasp::CameraIntrinsics::tumFreiburg1();
  const gasp::Undistortion u(k);
  EXPECT_THROW(u.applyToDepth(cv::Mat(10, 10, CV_32FC1, cv::Scalar(1.0f))), gasp::Error);  // size
  EXPECT_THROW(u.applyToDepth(cv::Mat(k.height, k.width, CV_8UC1, cv::Scalar(1))), gasp::Error);  // type
  EXPECT_THROW(u.applyToImage(cv::Mat(10, 10, CV_8UC3)), gasp::Error);
  auto bad = k;
  bad.distortion[0] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(gasp::Undistortion{bad}, gasp::Error);
  bad = k;
  bad.fx = 0.0;
  EXPECT_THROW(gasp::Undistortion{bad}, gasp::Error);
}
