// Depth superpixels on synthetic frames with exact ground truth (scene "room" unless stated).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <future>
#include <numeric>
#include <string>
#include <vector>

#include "gasp/sim/scene.h"
#include "gasp/sim/simulation.h"
#include "gasp/superpixels/depth_superpixels.h"
#include "segmentation_checks.h"

namespace {

gasp::sim::SimulatedFrame frameOf(const std::string& scene, int index, bool noise = true) {
  gasp::sim::SimulationOptions opt;
  opt.scene = scene;
  if (!noise) opt.noise = gasp::sim::KinectNoiseModel::exact();
  return gasp::sim::Simulation(opt).frame(index);
}

/// Patches on one ground-truth surface (>= 90% of their pixels on it) over every frame of a scene.
struct SceneEdges {
  double share = 0.0;  ///< over all the scene's patches
  double worst = 1.0;  ///< of a single frame
  int worst_frame = 0;
  std::vector<double> per_frame;
};

SceneEdges edgesOfScene(const std::string& scene, const gasp::SuperpixelParams& p) {
  gasp::sim::SimulationOptions opt;
  opt.scene = scene;
  const gasp::sim::Simulation sim(opt);
  SceneEdges out;
  gasp::test::SurfacePurity total;
  for (int index = 0; index < sim.size(); ++index) {
    const auto f = sim.frame(index);
    const auto seg = gasp::segmentDepthSuperpixels(f.depth, gasp::CameraIntrinsics::rosDefault(), p);
    const auto purity = gasp::test::surfacePurity(seg, f.labels);
    total.patches_on_one_surface += purity.patches_on_one_surface;
    total.patches += purity.patches;
    out.per_frame.push_back(purity.shareOnOneSurface());
    if (purity.patches > 0 && purity.shareOnOneSurface() < out.worst) {
      out.worst = purity.shareOnOneSurface();
      out.worst_frame = index;
    }
  }
  out.share = total.shareOnOneSurface();
  std::printf("%s, %d frames: %.4f of %d patches on one surface; worst frame %d: %.4f\n  frames 0-%d:", scene.c_str(),
              sim.size(), out.share, total.patches, out.worst_frame, out.worst, sim.size() - 1);
  for (double share : out.per_frame) std::printf(" %.3f", share);
  std::printf("\n");
  return out;
}

}  // namespace

TEST(SuperpixelsSynthetic, PatchesAreContiguousAndCoverTheView) {
  for (int index : {0, 25, 50}) {
    const auto f = frameOf("room", index);
    const auto seg = gasp::segmentDepthSuperpixels(f.depth, gasp::CameraIntrinsics::rosDefault());
    std::printf("frame %d: %zu patches, coverage %.4f\n", index, seg.patches.size(), seg.stats.coverage());
    EXPECT_EQ(gasp::test::countNonContiguousPatches(seg), 0);
    EXPECT_GE(seg.stats.coverage(), 0.95);
    EXPECT_EQ(seg.stats.assigned_pixels + seg.stats.dropped_pixels, seg.stats.valid_pixels);
    for (const auto& p : seg.patches) {
      ASSERT_NEAR(p.normal.norm(), 1.0, 1e-6);
      ASSERT_LT(p.normal.dot(p.centroid), 0.0) << "normals face the camera";
      ASSERT_GT(p.area_m2, 0.0);
    }
  }
}

TEST(SuperpixelsSynthetic, PatchesRespectSurfaceEdges) {
  // The target: 98% of the patches of synthetic scenes, measured over every frame of each
  // scene's sequence (docs/superpixels.md, "Edges"). Single frames fall below it where walls are
  // 4-5 m away (room frame 0: 0.970) -- guarded at the level reached. The scenes of the room tour:
  // the plane-dominated ones hold objects thinner than a depth step the segmentation can see (a
  // 1 cm cable, 3 cm chair legs on a floor; docs/superpixels.md, "Edges"), whose patches are
  // measured in docs/experiments/2026-11-28-plane-dominated-scenes.md.
  // The walked scenes (two_rooms) see walls up to the 6 m range limit, farther than the room
  // tour's: their single frames are guarded at the lower level they reach.
  for (const std::string& scene : gasp::sim::sceneNames()) {
    const gasp::sim::Scene s = gasp::sim::makeScene(scene);
    if (s.hand_held) continue;
    const SceneEdges e = edgesOfScene(scene, gasp::SuperpixelParams{});
    EXPECT_GE(e.share, 0.98) << scene;
    EXPECT_GE(e.worst, s.walk.empty() ? 0.965 : 0.94) << scene << " frame " << e.worst_frame;
  }
}

TEST(SuperpixelsSynthetic, StepBordersKeepFarWallsApart) {
  // The optional step borders (off by default) on the room, whose first frames face a picture on a
  // wall 4 m away: measured 0.979 / 0.990 / 0.987 for frames 0 / 10 / 20 (defaults 0.970 / 0.977 /
  // 0.974), 0.9895 over the 60 frames.
  gasp::SuperpixelParams p;
  p.borders.step_borders = true;
  const SceneEdges e = edgesOfScene("room", p);
  ASSERT_GT(e.per_frame.size(), 20u);
  EXPECT_GE(e.share, 0.985);
  EXPECT_GE(e.per_frame[0], 0.975);
  EXPECT_GE(e.per_frame[10], 0.985);
  EXPECT_GE(e.per_frame[20], 0.985);
}

TEST(SuperpixelsSynthetic, AreaIsRegularOnPlanarSurfaces) {
  // The "plane" scene: one plane filling the view. Patches cut by the image border are left out
  // of the statistic (their area depends on where the border cuts them).
  for (bool noise : {false, true}) {
    const auto f = frameOf("plane", 0, noise);
    const auto seg = gasp::segmentDepthSuperpixels(f.depth, gasp::CameraIntrinsics::rosDefault());
    std::vector<double> areas;
    for (const auto& p : seg.patches)
      if (p.bbox.x > 0 && p.bbox.y > 0 && p.bbox.br().x < f.depth.cols && p.bbox.br().y < f.depth.rows)
        areas.push_back(p.area_m2);
    ASSERT_GT(areas.size(), 20u);
    const double mean = std::accumulate(areas.begin(), areas.end(), 0.0) / static_cast<double>(areas.size());
    double var = 0.0;
    for (double a : areas) var += (a - mean) * (a - mean);
    const double cv = std::sqrt(var / static_cast<double>(areas.size())) / mean;
    std::printf("plane (%s): %zu interior patches, mean area %.1f cm^2, cv %.3f\n", noise ? "noise" : "exact",
                areas.size(), mean * 1e4, cv);
    EXPECT_LE(cv, 0.30);
    EXPECT_NEAR(mean, gasp::SuperpixelParams{}.target_patch_area_m2, 0.35 * gasp::SuperpixelParams{}.target_patch_area_m2);
  }
}

TEST(SuperpixelsSynthetic, SameInputGivesIdenticalLabels) {
  const auto f = frameOf("repeated", 10);
  const auto a = gasp::segmentDepthSuperpixels(f.depth, gasp::CameraIntrinsics::rosDefault());
  const auto b = gasp::segmentDepthSuperpixels(f.depth, gasp::CameraIntrinsics::rosDefault());
  ASSERT_EQ(a.patches.size(), b.patches.size());
  EXPECT_EQ(cv::countNonZero(a.labels != b.labels), 0);
  gasp::SuperpixelParams other;
  other.kmeans.seed = 7;  // another seeding order gives another (equally valid) decomposition
  const auto c = gasp::segmentDepthSuperpixels(f.depth, gasp::CameraIntrinsics::rosDefault(), other);
  EXPECT_GT(cv::countNonZero(a.labels != c.labels), 0);
}

TEST(SuperpixelsSynthetic, ConcurrentCallsGiveTheSameLabels) {
  // The pair pipeline segments two views at once: calls share no state.
  const auto f = frameOf("room", 30);
  const auto k = gasp::CameraIntrinsics::rosDefault();
  const auto alone = gasp::segmentDepthSuperpixels(f.depth, k);
  auto other = std::async(std::launch::async, [&] { return gasp::segmentDepthSuperpixels(f.depth, k); });
  const auto here = gasp::segmentDepthSuperpixels(f.depth, k);
  const auto there = other.get();
  EXPECT_EQ(cv::countNonZero(alone.labels != here.labels), 0);
  EXPECT_EQ(cv::countNonZero(alone.labels != there.labels), 0);
}

TEST(SuperpixelsSynthetic, FullResolutionProcessingStillHolds) {
  // processing_step_px = 1: every stage at full resolution (no grid, no refinement).
  gasp::SuperpixelParams p;
  p.processing_step_px = 1;
  const auto f = frameOf("room", 30);
  const auto seg = gasp::segmentDepthSuperpixels(f.depth, gasp::CameraIntrinsics::rosDefault(), p);
  std::printf("full resolution, frame 30: %zu patches, coverage %.4f\n", seg.patches.size(), seg.stats.coverage());
  EXPECT_EQ(gasp::test::countNonContiguousPatches(seg), 0);
  EXPECT_GE(seg.stats.coverage(), 0.95);
  EXPECT_GT(seg.patches.size(), 1000u);
}

TEST(SuperpixelsSynthetic, AdjacencyIsSymmetricAndLocal) {
  const auto f = frameOf("sparse", 5);
  const auto seg = gasp::segmentDepthSuperpixels(f.depth, gasp::CameraIntrinsics::rosDefault());
  ASSERT_EQ(seg.adjacency.size(), seg.patches.size());
  for (std::size_t i = 0; i < seg.adjacency.size(); ++i)
    for (int j : seg.adjacency[i]) {
      const auto& other = seg.adjacency[static_cast<std::size_t>(j)];
      EXPECT_TRUE(std::binary_search(other.begin(), other.end(), static_cast<int>(i)));
      const double gap = (seg.patches[i].centroid - seg.patches[static_cast<std::size_t>(j)].centroid).norm();
      EXPECT_LT(gap, 4.0 * (seg.patches[i].radius() + seg.patches[static_cast<std::size_t>(j)].radius()) + 0.3);
    }
}
