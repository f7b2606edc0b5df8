// A view as bytes and back (view_bytes.h): exactly the view, so that a registration on views read
// back is the registration on the views made; bytes that are not a view's are errors.
#include <gtest/gtest.h>

#include <string>

#include "gasp/core/error.h"
#include "gasp/pipeline/pair_registration.h"
#include "gasp/pipeline/range_view.h"
#include "gasp/pipeline/view_bytes.h"
#include "gasp/sim/lidar.h"
#include "gasp/sim/scene.h"
#include "gasp/sim/simulation.h"

namespace {

bool sameMat(const cv::Mat& a, const cv::Mat& b) {
  if (a.empty() || b.empty()) return a.empty() && b.empty();
  if (a.size() != b.size() || a.type() != b.type()) return false;
  for (int r = 0; r < a.rows; ++r)
    if (std::memcmp(a.ptr(r), b.ptr(r), static_cast<std::size_t>(a.cols) * a.elemSize()) != 0) return false;
  return true;
}

/// Every field the bytes hold, compared exactly.
void expectSameView(const gasp::DepthView& a, const gasp::DepthView& b) {
  EXPECT_TRUE(sameMat(a.depth_m, b.depth_m));
  EXPECT_TRUE(sameMat(a.segmentation.labels, b.segmentation.labels));
  ASSERT_EQ(a.segmentation.patches.size(), b.segmentation.patches.size());
  for (std::size_t i = 0; i < a.segmentation.patches.size(); ++i) {
    const gasp::SurfacePatch &p = a.segmentation.patches[i], &q = b.segmentation.patches[i];
    EXPECT_EQ(p.id, q.id);
    EXPECT_TRUE(p.centroid == q.centroid && p.normal == q.normal && p.covariance == q.covariance) << i;
    EXPECT_EQ(p.area_m2, q.area_m2);
    EXPECT_EQ(p.pixel_count, q.pixel_count);
    EXPECT_EQ(p.planarity, q.planarity);
    EXPECT_EQ(p.bbox, q.bbox);
  }
  EXPECT_EQ(a.segmentation.adjacency, b.segmentation.adjacency);
  EXPECT_EQ(a.segmentation.stats.valid_pixels, b.segmentation.stats.valid_pixels);
  EXPECT_EQ(a.segmentation.stats.assigned_pixels, b.segmentation.stats.assigned_pixels);
  EXPECT_EQ(a.segmentation.stats.dropped_pixels, b.segmentation.stats.dropped_pixels);
  ASSERT_EQ(a.projection.isPinhole(), b.projection.isPinhole());
  EXPECT_EQ(a.projection.width(), b.projection.width());
  EXPECT_EQ(a.projection.height(), b.projection.height());
  ASSERT_EQ(static_cast<bool>(a.returns), static_cast<bool>(b.returns));
}

/// The same registration, to the last bit.
void expectSameRegistration(const gasp::PairResult& a, const gasp::PairResult& b) {
  EXPECT_EQ(a.pose.success, b.pose.success);
  EXPECT_EQ(a.pose.reason, b.pose.reason);
  EXPECT_EQ(a.pose.num_inliers, b.pose.num_inliers);
  EXPECT_TRUE(a.pose.T_target_source.matrix() == b.pose.T_target_source.matrix());
  EXPECT_TRUE(a.edge_information == b.edge_information);
}

}  // namespace

TEST(ViewBytes, CameraAndLidarViewsReadBackExactlyAndRegisterTheSame) {
  gasp::sim::SimulationOptions o;
  o.frames = 20;
  const gasp::sim::Simulation sim(o);
  const gasp::PairParams camera;
  const gasp::DepthView a = gasp::makeDepthView(sim.frame(0).depth, o.intrinsics, camera.segment);
  const gasp::DepthView b = gasp::makeDepthView(sim.frame(6).depth, o.intrinsics, camera.segment);
  const gasp::DepthView a2 = gasp::viewFromBytes(gasp::viewBytes(a), camera.segment);
  const gasp::DepthView b2 = gasp::viewFromBytes(gasp::viewBytes(b), camera.segment);
  ASSERT_FALSE(a.segmentation.patches.empty());
  expectSameView(a, a2);
  expectSameRegistration(gasp::registerViews(a, b, camera), gasp::registerViews(a2, b2, camera));

  // Two sweeps of the room: the grid, its rays and the sweep (its returns fitted again) too.
  const gasp::PairParams lidar = gasp::lidarPairParams();
  const gasp::sim::Scene room = gasp::sim::makeScene("room");
  gasp::Isometry3 T = gasp::Isometry3::Identity();
  T.translation() = Eigen::Vector3d(0.2, 0.1, 1.2);
  const gasp::RangeScan s0 = gasp::sim::simulateLidarScan(room, gasp::sim::lidarSensor(16), T);
  T.translation().x() += 0.4;
  T.linear() = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const gasp::RangeScan s1 = gasp::sim::simulateLidarScan(room, gasp::sim::lidarSensor(16), T);
  const gasp::DepthView c = gasp::makeRangeView(s0, lidar.segment, lidar.returns);
  const gasp::DepthView d = gasp::makeRangeView(s1, lidar.segment, lidar.returns);
  const gasp::DepthView c2 = gasp::viewFromBytes(gasp::viewBytes(c), lidar.segment, lidar.returns);
  const gasp::DepthView d2 = gasp::viewFromBytes(gasp::viewBytes(d), lidar.segment, lidar.returns);
  expectSameView(c, c2);
  EXPECT_TRUE(sameMat(c.projection.grid().ray, c2.projection.grid().ray));
  EXPECT_TRUE(sameMat(c.returns->scan().range_m, c2.returns->scan().range_m));
  const gasp::PairResult lr = gasp::registerViews(c, d, lidar);
  EXPECT_TRUE(lr.pose.success) << lr.pose.reason;
  expectSameRegistration(lr, gasp::registerViews(c2, d2, lidar));

  // Not a view's bytes.
  const std::string bytes = gasp::viewBytes(a);
  EXPECT_THROW((void)gasp::viewFromBytes("", camera.segment), gasp::Error);
  EXPECT_THROW((void)gasp::viewFromBytes("GVW2" + bytes.substr(4), camera.segment), gasp::Error);
  for (const std::size_t cut : {std::size_t{20}, bytes.size() / 2, bytes.size() - 1}) {
    try {
      (void)gasp::viewFromBytes(bytes.substr(0, cut), camera.segment);
      ADD_FAILURE() << "read " << cut << " of " << bytes.size() << " bytes";
    } catch (const gasp::Error& e) {
      EXPECT_NE(std::string(e.what()).find("view bytes: "), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW((void)gasp::viewFromBytes(bytes + "x", camera.segment), gasp::Error);
}
