#include <gtest/gtest.h>

#include <cmath>

#include "gasp/superpixels/normals.h"

namespace {

/// Depth of the plane n . p = d seen by a pinhole camera (exact, no noise).
cv::Mat planeDepth(const gasp::CameraIntrinsics& k, const Eigen::Vector3d& n, double d) {
  cv::Mat depth(k.height, k.width, CV_32FC1);
  for (int v = 0; v < k.height; ++v)
    for (int u = 0; u < k.width; ++u) {
      const Eigen::Vector3d ray((u - k.cx) / k.fx, (v - k.cy) / k.fy, 1.0);
      depth.at<float>(v, u) = static_cast<float>(d / n.dot(ray));
    }
  return depth;
}

}  // namespace

TEST(Normals, TiltedPlaneGivesItsNormalEverywhere) {
  const auto k = gasp::CameraIntrinsics::rosDefault();
  const Eigen::Vector3d n = Eigen::Vector3d(0.3, -0.4, 1.0).normalized();  // facing away
  const auto cloud = gasp::backProject(planeDepth(k, n, 2.0), k);
  const gasp::SuperpixelParams p;
  const gasp::DepthLinks links(cloud, p);
  const auto normals = gasp::estimateNormals(cloud, links, p);
  int with_normal = 0;
  for (int v = 0; v < k.height; ++v)
    for (int u = 0; u < k.width; ++u) {
      if (!normals.hasNormal(u, v)) continue;
      ++with_normal;
      const cv::Vec3f m = normals.normals.at<cv::Vec3f>(v, u);
      ASSERT_NEAR(-Eigen::Vector3d(m[0], m[1], m[2]).dot(n), 1.0, 1e-4) << u << "," << v;  // faces the camera
      ASSERT_LT(normals.crease.at<float>(v, u), 0.01f);
    }
  // Only the image border (window half-size) lacks normals.
  EXPECT_GT(with_normal, k.width * k.height * 9 / 10);
}

TEST(Normals, CreaseAndDiscontinuityAreSetAside) {
  // Left half: a wall at z = 2; right half: a plane receding at 45 degrees from the same line,
  // so the depth is continuous but the normal turns by 45 degrees at u = 320. Plus a box at
  // rows 100-140 floating 0.5 m in front: a depth discontinuity.
  const auto k = gasp::CameraIntrinsics::rosDefault();
  cv::Mat depth(k.height, k.width, CV_32FC1);
  for (int v = 0; v < k.height; ++v)
    for (int u = 0; u < k.width; ++u) {
      const double x = (u - k.cx) / k.fx;  // ray slope
      const double x0 = (320 - k.cx) / k.fx;
      depth.at<float>(v, u) = u < 320 ? 2.0f : static_cast<float>(2.0 * (1.0 - x0) / (1.0 - x));
      if (v >= 100 && v < 140) depth.at<float>(v, u) -= 0.5f;
    }
  const auto cloud = gasp::backProject(depth, k);
  const gasp::SuperpixelParams p;
  const gasp::DepthLinks links(cloud, p);
  const auto normals = gasp::estimateNormals(cloud, links, p);
  const float max_crease = static_cast<float>(p.surfaces.max_crease_angle_deg * M_PI / 180.0);
  // At the crease: either no normal or a crease angle over the threshold.
  const bool set_aside = !normals.hasNormal(320, 300) || normals.crease.at<float>(300, 320) > max_crease;
  EXPECT_TRUE(set_aside);
  // Next to the depth discontinuity: no normal (windows never cross it).
  EXPECT_FALSE(normals.hasNormal(200, 99));
  EXPECT_FALSE(normals.hasNormal(200, 100));
  EXPECT_FALSE(links.down(99 * k.width + 200));
  // Far from both: a normal, no crease.
  EXPECT_TRUE(normals.hasNormal(100, 300));
  EXPECT_LT(normals.crease.at<float>(300, 100), 0.02f);
}
