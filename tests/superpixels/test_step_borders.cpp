// Step borders (src/step_borders.h): a picture 4 cm in front of a wall 4 m away, where a pixel's
// depth cannot tell them apart (Kinect noise ~3 cm, disparity levels 4 cm): the patch borders
// follow the picture's outline.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "gasp/sim/scene.h"
#include "gasp/superpixels/depth_superpixels.h"
#include "noisy_view.h"

namespace {

using gasp::Isometry3;

/// A 5 x 3 m wall 4 m in front of the camera, turned 20 deg about the vertical, with (when
/// `relief` > 0) a 0.8 x 0.6 m picture `relief` metres in front of it.
gasp::sim::Scene wall(double relief) {
  gasp::sim::Scene s;
  const double yaw = 20.0 * M_PI / 180.0;
  const Eigen::Vector3d along(std::sin(yaw), std::cos(yaw), 0.0);
  const Isometry3 T = gasp::test::uprightFrame(along, Eigen::Vector3d(4.0, 0.0, 0.0));  // z away from the camera
  s.add("wall", gasp::sim::Rectangle{2.5, 1.5}, T);
  if (relief > 0.0) {
    Isometry3 P = T;
    P.translation() = T * Eigen::Vector3d(0.3, 0.2, -relief);
    s.add("picture", gasp::sim::Rectangle{0.4, 0.3}, P);
  }
  return s;
}

gasp::test::ScoredSegmentation segmentAndScore(const gasp::sim::Scene& scene, bool step_borders) {
  gasp::SuperpixelParams p;
  p.borders.step_borders = step_borders;
  return gasp::test::segmentNoisyView(scene, p);
}

}  // namespace

TEST(StepBorders, BordersFollowAPictureFourCentimetresProudFourMetresAway) {
  const auto scene = wall(0.04);
  const auto off = segmentAndScore(scene, false);
  const auto on = segmentAndScore(scene, true);
  std::printf("picture: %zu patches; on one surface %.3f -> %.3f, pixels off their patch's surface %d -> %d\n",
              on.seg.patches.size(), off.purity.shareOnOneSurface(), on.purity.shareOnOneSurface(),
              off.purity.pixels_off_majority, on.purity.pixels_off_majority);
  EXPECT_GE(on.purity.shareOnOneSurface(), 0.98);
  EXPECT_LT(on.purity.pixels_off_majority, off.purity.pixels_off_majority / 2);
}

TEST(StepBorders, AWallAloneIsNotCut) {
  // No step: one surface plane, nothing to cut between -- the labels are those without the stage.
  const auto scene = wall(0.0);
  const auto off = segmentAndScore(scene, false);
  const auto on = segmentAndScore(scene, true);
  EXPECT_EQ(cv::countNonZero(on.seg.labels != off.seg.labels), 0);
}
