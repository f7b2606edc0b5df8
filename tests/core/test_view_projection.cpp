#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "gasp/core/error.h"
#include "gasp/core/point_cloud.h"
#include "gasp/core/view_projection.h"

namespace {

using gasp::SphericalGrid;
using gasp::ViewProjection;

constexpr double kDeg = M_PI / 180.0;

/// 16 rows from -15 to +15 deg, a whole clockwise turn in 180 columns of 2 deg.
SphericalGrid vlp16Turn() {
  SphericalGrid g;
  for (int i = 0; i < 16; ++i) g.elevation_rad.push_back((-15.0 + 2.0 * i) * kDeg);
  g.azimuth_first_rad = M_PI;
  g.azimuth_step_rad = -2.0 * kDeg;
  g.columns = 180;
  return g;
}

TEST(ViewProjection, APinholeIsTheIntrinsics) {
  const gasp::CameraIntrinsics k = gasp::CameraIntrinsics::tumFreiburg3();
  const ViewProjection p = k;
  EXPECT_TRUE(p.isPinhole());
  EXPECT_EQ(p.width(), 640);
  // Exactly the intrinsics' arithmetic: the camera's results do not move.
  const Eigen::Vector3d q = p.unproject(100.0, 200.0, 2.5);
  EXPECT_TRUE(q == k.unproject(100.0, 200.0, 2.5));
  EXPECT_EQ(p.depth(q), q.z());
  double u = 0, v = 0, ku = 0, kv = 0;
  ASSERT_TRUE(p.project(q, u, v));
  ASSERT_TRUE(k.project(q, ku, kv));
  EXPECT_EQ(u, ku);
  EXPECT_EQ(v, kv);
  EXPECT_EQ(p.frontalArea(Eigen::Vector3f(0, 0, 2)), 2.0f * 2.0f * static_cast<float>(1.0 / (k.fx * k.fy)));
  EXPECT_DOUBLE_EQ(p.pixelsPerRadian(), k.fx);
  EXPECT_THROW(p.grid(), gasp::Error);
}

TEST(ViewProjection, ASphericalCellProjectsBackToItselfAcrossTheSeam) {
  const ViewProjection p = ViewProjection::spherical(vlp16Turn());
  EXPECT_FALSE(p.isPinhole());
  EXPECT_EQ(p.width(), 180);
  EXPECT_EQ(p.height(), 16);
  EXPECT_THROW(p.pinhole(), gasp::Error);
  for (const int row : {0, 7, 15})
    for (const int col : {0, 1, 89, 178, 179}) {
      const Eigen::Vector3d q = p.unproject(col, row, 12.0);
      EXPECT_NEAR(p.depth(q), 12.0, 1e-9);
      double u = -1, v = -1;
      ASSERT_TRUE(p.project(q, u, v)) << row << " " << col;
      EXPECT_NEAR(u, col, 1e-9);
      EXPECT_NEAR(v, row, 1e-9);
    }
  // Column 0 looks backwards (azimuth 180 deg); 45 columns clockwise on, azimuth 90 deg (left).
  EXPECT_TRUE(p.ray(0, 7.5).isApprox(Eigen::Vector3d(-1, 0, 0), 1e-9));
  EXPECT_TRUE(p.ray(45, 7.5).isApprox(Eigen::Vector3d(0, 1, 0), 1e-9));
  // Between rows: the elevation interpolated; beyond half a pitch from the end rows: outside.
  double u = 0, v = 0;
  ASSERT_TRUE(p.project(Eigen::Vector3d(std::cos(0.5 * kDeg), 0.0, std::sin(0.5 * kDeg)), u, v));
  EXPECT_NEAR(v, 7.75, 1e-9);
  EXPECT_NEAR(u, 90.0, 1e-9);
  EXPECT_FALSE(p.project(Eigen::Vector3d(std::cos(16.5 * kDeg), 0.0, std::sin(16.5 * kDeg)), u, v));
  EXPECT_FALSE(p.project(Eigen::Vector3d::Zero(), u, v));
  // Frontal area: range^2 cos(elevation) * azimuth step * row pitch.
  const Eigen::Vector3f q = p.unproject(10, 15, 5.0).cast<float>();
  EXPECT_NEAR(p.frontalArea(q), 25.0 * std::cos(15.0 * kDeg) * 4.0 * kDeg * kDeg, 1e-6);
  EXPECT_NEAR(p.pixelsPerRadian(), 1.0 / (2.0 * kDeg), 1e-9);
}

TEST(ViewProjection, APartialSweepRejectsAzimuthsOutsideIt) {
  SphericalGrid g = vlp16Turn();
  g.columns = 30;  // 180 .. 122 deg
  const ViewProjection p = ViewProjection::spherical(g);
  double u = 0, v = 0;
  EXPECT_TRUE(p.project(Eigen::Vector3d(-1.0, 0.5, 0.0), u, v));   // 153 deg
  EXPECT_NEAR(u, (180.0 - std::atan2(0.5, -1.0) / kDeg) / 2.0, 1e-9);
  EXPECT_FALSE(p.project(Eigen::Vector3d(1.0, 0.0, 0.0), u, v));   // straight ahead
  EXPECT_FALSE(p.project(Eigen::Vector3d(-1.0, -0.1, 0.0), u, v));  // just past the first column
}

TEST(ViewProjection, ACropKeepsEachCellsRay) {
  SphericalGrid g = vlp16Turn();
  g.ray = cv::Mat::zeros(16, 180, CV_32FC3);
  const Eigen::Vector3f odd = Eigen::Vector3f(1, 1, 0.2f).normalized();
  g.ray.at<cv::Vec3f>(5, 40) = cv::Vec3f(odd.x(), odd.y(), odd.z());
  const ViewProjection p = ViewProjection::spherical(g);
  const ViewProjection c = p.cropped(30, 2, 20, 6);
  EXPECT_EQ(c.width(), 20);
  EXPECT_EQ(c.height(), 6);
  EXPECT_TRUE(c.ray(10, 3).isApprox(odd.cast<double>(), 1e-6));
  EXPECT_TRUE(c.ray(4, 1).isApprox(p.ray(34, 3), 1e-12));
  EXPECT_FLOAT_EQ(c.frontalArea(Eigen::Vector3f(3, 0, 0)), p.frontalArea(Eigen::Vector3f(3, 0, 0)));
  EXPECT_THROW(p.cropped(170, 0, 20, 16), gasp::Error);
}

TEST(ViewProjection, BackProjectedRangesLieOnTheirRays) {
  const ViewProjection p = ViewProjection::spherical(vlp16Turn());
  cv::Mat range(16, 180, CV_32FC1, cv::Scalar(0.0f));
  range.at<float>(3, 50) = 7.5f;
  const gasp::OrganizedPointCloud cloud = gasp::backProject(range, p);
  EXPECT_TRUE(cloud.range_depth);
  EXPECT_EQ(cloud.countValid(), 1u);
  EXPECT_TRUE(cloud.at(50, 3).cast<double>().isApprox(p.unproject(50, 3, 7.5), 1e-6));
  EXPECT_NEAR(cloud.depth(cloud.at(50, 3)), 7.5f, 1e-5);
  EXPECT_THROW(gasp::backProject(cv::Mat(16, 179, CV_32FC1, cv::Scalar(1.0f)), p), gasp::Error);
}

TEST(ViewProjection, AnInvalidGridIsRefusedWithItsReason) {
  const auto reason = [](SphericalGrid g) {
    try {
      ViewProjection::spherical(std::move(g));
    } catch (const gasp::Error& e) {
      return std::string(e.what());
    }
    return std::string("(accepted)");
  };
  SphericalGrid g = vlp16Turn();
  std::swap(g.elevation_rad[3], g.elevation_rad[4]);
  EXPECT_NE(reason(g).find("strictly ascending (row 4)"), std::string::npos) << reason(g);
  g = vlp16Turn();
  g.columns = 200;  // 400 deg
  EXPECT_NE(reason(g).find("cover more than one turn"), std::string::npos) << reason(g);
  g = vlp16Turn();
  g.azimuth_step_rad = 0.0;
  EXPECT_NE(reason(g).find("non-zero"), std::string::npos) << reason(g);
  g = vlp16Turn();
  g.ray = cv::Mat::zeros(16, 10, CV_32FC3);
  EXPECT_NE(reason(g).find("ray table must be CV_32FC3 of 16 x 180"), std::string::npos) << reason(g);
}

TEST(ViewProjection, ATurnOfAFractionalNumberOfColumnsHasAGapAtTheSeam) {
  // 257 cells of 1.4 deg (a binned HDL-32E sweep): 359.8 deg, the last 0.2 deg is no pixel.
  SphericalGrid g = vlp16Turn();
  g.azimuth_first_rad = 0.0;
  g.azimuth_step_rad = -1.4 * kDeg;
  g.columns = 257;
  const ViewProjection p = ViewProjection::spherical(g);
  const auto at = [](double azimuth_deg) {
    return Eigen::Vector3d(std::cos(azimuth_deg * kDeg), std::sin(azimuth_deg * kDeg), 0.0);
  };
  double u = 0, v = 0;
  ASSERT_TRUE(p.project(at(-1.4 * 256), u, v));  // the last column
  EXPECT_NEAR(u, 256.0, 1e-9);
  EXPECT_FALSE(p.project(at(-1.4 * 256.57), u, v));  // in the gap: no column within half a step
  ASSERT_TRUE(p.project(at(0.5), u, v));             // just past column 0, on the seam's other side
  EXPECT_NEAR(u, -0.5 / 1.4, 1e-9);
  EXPECT_EQ(std::lround(u), 0);
}

TEST(ViewProjection, WrapToPiIsTheRemainderOfATurn) {
  // The cheap path (already within [-pi, pi]) and the call it saves must agree everywhere,
  // at the ends and many turns away included.
  for (double a = -25.0; a <= 25.0; a += 0.001)
    EXPECT_EQ(gasp::wrapToPi(a), std::remainder(a, 2.0 * M_PI)) << a;
  for (const double a : {M_PI, -M_PI, std::nextafter(M_PI, 4.0), std::nextafter(-M_PI, -4.0), 3.0 * M_PI, 0.0, -0.0}) {
    EXPECT_EQ(gasp::wrapToPi(a), std::remainder(a, 2.0 * M_PI)) << a;
    EXPECT_EQ(std::signbit(gasp::wrapToPi(a)), std::signbit(std::remainder(a, 2.0 * M_PI))) << a;
  }
  EXPECT_TRUE(std::isnan(gasp::wrapToPi(std::nan(""))));
  EXPECT_TRUE(std::isnan(gasp::wrapToPi(HUGE_VAL)));
  EXPECT_TRUE(std::isnan(gasp::wrapToPi(-HUGE_VAL)));
}

}  // namespace
