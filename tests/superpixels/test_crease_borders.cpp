// Crease borders (src/crease_borders.h): at a crease 4 m away, where Kinect noise is a few cm,
// patch borders follow the line where the two planes meet.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>

#include "gasp/sim/noise_model.h"
#include "gasp/sim/renderer.h"
#include "gasp/sim/scene.h"
#include "gasp/superpixels/depth_superpixels.h"
#include "segmentation_checks.h"

namespace {

using gasp::Isometry3;

/// Two 4 x 3 m walls meeting along a vertical line 4 m in front of the camera, each at 45 deg to
/// the line of sight: a concave crease (a room's corner) or a convex one (a box's edge).
gasp::sim::Scene corner(bool concave) {
  gasp::sim::Scene s;
  const Eigen::Vector3d apex(4.0, 0.0, 0.0);
  for (int side : {-1, 1}) {
    const Eigen::Vector3d along = Eigen::Vector3d(concave ? -1.0 : 1.0, side, 0.0).normalized();
    Isometry3 T = Isometry3::Identity();
    T.linear().col(0) = along;
    T.linear().col(1) = Eigen::Vector3d::UnitZ();
    T.linear().col(2) = along.cross(Eigen::Vector3d::UnitZ());
    T.translation() = apex + 2.0 * along;
    s.add(side < 0 ? "wall_right" : "wall_left", gasp::sim::Rectangle{2.0, 1.5}, T);
  }
  return s;
}

struct Purity {
  double share_on_one_surface = 0.0;  ///< patches with >= 90% of their pixels on one surface
  int pixels_off_majority = 0;        ///< pixels on another surface than their patch's majority
  std::size_t patches = 0;
};

Purity segmentAndScore(const gasp::sim::Scene& scene, bool crease_borders) {
  const auto K = gasp::CameraIntrinsics::rosDefault();
  Isometry3 T_world_camera = Isometry3::Identity();  // optical frame: z forward = world x
  T_world_camera.linear() << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  const auto rendered = gasp::sim::renderFrame(scene, K, T_world_camera);
  const cv::Mat depth = gasp::sim::sensorDepth(rendered, gasp::sim::KinectNoiseModel{}, K, 7, 0);
  gasp::SuperpixelParams p;
  p.crease_borders = crease_borders;
  const auto seg = gasp::segmentDepthSuperpixels(depth, K, p);
  EXPECT_EQ(gasp::test::countNonContiguousPatches(seg), 0);
  std::vector<std::map<int, int>> votes(seg.patches.size());
  for (int v = 0; v < depth.rows; ++v)
    for (int u = 0; u < depth.cols; ++u) {
      const int l = seg.labels.at<int>(v, u);
      if (l >= 0) ++votes[static_cast<std::size_t>(l)][rendered.surface_id.at<std::uint16_t>(v, u)];
    }
  Purity out;
  out.patches = seg.patches.size();
  int pure = 0;
  for (std::size_t i = 0; i < votes.size(); ++i) {
    int best = 0;
    for (const auto& [surface, n] : votes[i]) best = std::max(best, n);
    pure += best >= 0.9 * seg.patches[i].pixel_count;
    out.pixels_off_majority += seg.patches[i].pixel_count - best;
  }
  out.share_on_one_surface = static_cast<double>(pure) / static_cast<double>(seg.patches.size());
  return out;
}

}  // namespace

TEST(CreaseBorders, BordersFollowTheCreaseFourMetresAway) {
  for (bool concave : {true, false}) {
    const auto scene = corner(concave);
    const Purity off = segmentAndScore(scene, false);
    const Purity on = segmentAndScore(scene, true);
    std::printf("%s crease: %zu patches; on one surface %.3f -> %.3f, pixels off their patch's surface %d -> %d\n",
                concave ? "concave" : "convex", on.patches, off.share_on_one_surface, on.share_on_one_surface,
                off.pixels_off_majority, on.pixels_off_majority);
    EXPECT_GE(on.share_on_one_surface, 0.99);
    EXPECT_LT(on.pixels_off_majority, off.pixels_off_majority / 2);
  }
}

TEST(CreaseBorders, OffLeavesTheLabelsOfTheEarlierStages) {
  // With crease_borders off nothing else changes: a plane (no crease) gives the same labels.
  const auto K = gasp::CameraIntrinsics::rosDefault();
  cv::Mat depth(K.height, K.width, CV_32F, cv::Scalar(2.0f));
  gasp::SuperpixelParams on, off;
  off.crease_borders = false;
  const auto a = gasp::segmentDepthSuperpixels(depth, K, on);
  const auto b = gasp::segmentDepthSuperpixels(depth, K, off);
  EXPECT_EQ(cv::countNonZero(a.labels != b.labels), 0);
}
