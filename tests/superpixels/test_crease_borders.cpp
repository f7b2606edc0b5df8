// Crease borders (src/crease_borders.h): at a crease 4 m away, where Kinect noise is a few cm,
// patch borders follow the line where the two planes meet.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "gasp/sim/scene.h"
#include "gasp/superpixels/depth_superpixels.h"
#include "noisy_view.h"

namespace {

/// Two 4 x 3 m walls meeting along a vertical line 4 m in front of the camera, each at 45 deg to
/// the line of sight: a concave crease (a room's corner) or a convex one (a box's edge).
gasp::sim::Scene corner(bool concave) {
  gasp::sim::Scene s;
  const Eigen::Vector3d apex(4.0, 0.0, 0.0);
  for (int side : {-1, 1}) {
    const Eigen::Vector3d along = Eigen::Vector3d(concave ? -1.0 : 1.0, side, 0.0).normalized();
    s.add(side < 0 ? "wall_right" : "wall_left", gasp::sim::Rectangle{2.0, 1.5},
          gasp::test::uprightFrame(along, apex + 2.0 * along));
  }
  return s;
}

gasp::test::ScoredSegmentation segmentAndScore(const gasp::sim::Scene& scene, bool crease_borders) {
  gasp::SuperpixelParams p;
  p.borders.crease_borders = crease_borders;
  return gasp::test::segmentNoisyView(scene, p);
}

}  // namespace

TEST(CreaseBorders, BordersFollowTheCreaseFourMetresAway) {
  for (bool concave : {true, false}) {
    const auto scene = corner(concave);
    const auto off = segmentAndScore(scene, false);
    const auto on = segmentAndScore(scene, true);
    std::printf("%s crease: %zu patches; on one surface %.3f -> %.3f, pixels off their patch's surface %d -> %d\n",
                concave ? "concave" : "convex", on.seg.patches.size(), off.purity.shareOnOneSurface(),
                on.purity.shareOnOneSurface(), off.purity.pixels_off_majority, on.purity.pixels_off_majority);
    EXPECT_GE(on.purity.shareOnOneSurface(), 0.99);
    EXPECT_LT(on.purity.pixels_off_majority, off.purity.pixels_off_majority / 2);
  }
}

TEST(CreaseBorders, OffLeavesTheLabelsOfTheEarlierStages) {
  // With crease_borders off nothing else changes: a plane (no crease) gives the same labels.
  const auto K = gasp::CameraIntrinsics::rosDefault();
  cv::Mat depth(K.height, K.width, CV_32F, cv::Scalar(2.0f));
  gasp::SuperpixelParams on, off;
  off.borders.crease_borders = false;
  const auto a = gasp::segmentDepthSuperpixels(depth, K, on);
  const auto b = gasp::segmentDepthSuperpixels(depth, K, off);
  EXPECT_EQ(cv::countNonZero(a.labels != b.labels), 0);
}
