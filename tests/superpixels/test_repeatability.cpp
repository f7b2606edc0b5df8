// Repeatability of patches across views (issue acceptance): >= 80% on synthetic pairs including
// the 180-degree roll; >= 60% on fr1_xyz pairs 10 frames apart (test_segmentation_real.cpp).
#include <gtest/gtest.h>

#include <cstdio>

#include "gasp/sim/simulation.h"
#include "gasp/superpixels/depth_superpixels.h"
#include "gasp/superpixels/patch_repeatability.h"

namespace {

double repeatability(const gasp::sim::Simulation& sim, int i, int j) {
  const auto fa = sim.frame(i), fb = sim.frame(j);
  const auto& k = sim.options().intrinsics;
  const auto sa = gasp::segmentDepthSuperpixels(fa.depth, k);
  const auto sb = gasp::segmentDepthSuperpixels(fb.depth, k);
  const auto r = gasp::measureRepeatability(sa, sb, fb.depth, k,
                                            gasp::relativePose(fb.T_world_camera, fa.T_world_camera));
  std::printf("frames %d -> %d: %d of %d patches in the overlap, repeated %.3f\n", i, j, r.in_overlap,
              r.patches_a, r.fraction());
  return r.fraction();
}

}  // namespace

TEST(Repeatability, IdenticalViewsAreFullyRepeatable) {
  gasp::sim::SimulationOptions opt;
  opt.frames = 8;
  const gasp::sim::Simulation sim(opt);
  EXPECT_DOUBLE_EQ(repeatability(sim, 3, 3), 1.0);
}

class SyntheticSegment : public ::testing::TestWithParam<const char*> {};

TEST_P(SyntheticSegment, MostPatchesRecurBetweenTheSegmentEnds) {
  gasp::sim::SimulationOptions opt;  // default scene "room", 60 frames, Kinect noise
  const gasp::sim::Simulation sim(opt);
  const auto& seg = sim.path().segment(GetParam());
  // The segment's two end frames: the hard pair (wide baseline, pan with partial overlap,
  // occluder, 180-degree roll), in both directions.
  EXPECT_GE(repeatability(sim, seg.first_frame, seg.last_frame), 0.80);
  EXPECT_GE(repeatability(sim, seg.last_frame, seg.first_frame), 0.80);
}

INSTANTIATE_TEST_SUITE_P(Segments, SyntheticSegment,
                         ::testing::Values(gasp::sim::kWideBaseline, gasp::sim::kPartialOverlap,
                                           gasp::sim::kOccluderAppears, gasp::sim::kRoll180));
