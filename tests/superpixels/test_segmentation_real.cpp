// Depth superpixels on the real TUM frames in ../shared/data (skipped where absent).
#include <gtest/gtest.h>

#include <cstdio>

#include "gasp/core/tum_dataset.h"
#include "gasp/superpixels/depth_superpixels.h"
#include "gasp/superpixels/patch_repeatability.h"
#include "gasp_test_data.h"
#include "segmentation_checks.h"

namespace {

/// max_patches: views of a whole room floor (fr3 cabinet) have more patches than desk views.
void checkFrames(const std::string& dir, std::size_t step, std::size_t max_patches) {
  const auto ds = gasp::TumDataset::open(dir);
  for (std::size_t i = 0; i < ds.size(); i += step) {
    const auto seg = gasp::segmentDepthSuperpixels(ds.loadDepth(i), ds.intrinsics());
    std::printf("%s frame %zu: %zu patches, coverage %.4f (%zu valid pixels dropped as noise)\n",
                dir.c_str(), i, seg.patches.size(), seg.stats.coverage(), seg.stats.dropped_pixels);
    EXPECT_GE(seg.stats.coverage(), 0.95) << "frame " << i;
    EXPECT_EQ(gasp::test::countNonContiguousPatches(seg), 0) << "frame " << i;
    EXPECT_GE(seg.patches.size(), 100u) << "frame " << i;
    EXPECT_LE(seg.patches.size(), max_patches) << "frame " << i;
  }
}

}  // namespace

TEST(SuperpixelsReal, Fr1Desk9) {
  GASP_REQUIRE_DATA(dir, "tum/fr1_desk9");
  checkFrames(dir, 1, 1500);
}

TEST(SuperpixelsReal, Fr1Xyz) {
  GASP_REQUIRE_DATA(dir, "tum/fr1_xyz");
  checkFrames(dir, 97, 1500);
}

TEST(SuperpixelsReal, Fr3CabinetKeyframes) {
  GASP_REQUIRE_DATA(dir, "tum/fr3_cabinet_kf");
  checkFrames(dir, 3, 3500);
}

TEST(SuperpixelsReal, DeskFrameHasAFewHundredPatches) {
  GASP_REQUIRE_DATA(dir, "tum/fr1_xyz");
  const auto ds = gasp::TumDataset::open(dir);
  const auto seg = gasp::segmentDepthSuperpixels(ds.loadDepth(9), ds.intrinsics());
  EXPECT_GE(seg.patches.size(), 200u);
  EXPECT_LE(seg.patches.size(), 900u);
}

TEST(SuperpixelsReal, RepeatabilityOnFr1XyzPairsTenFramesApart) {
  GASP_REQUIRE_DATA(dir, "tum/fr1_xyz");
  const auto ds = gasp::TumDataset::open(dir);
  double sum = 0.0;
  int pairs = 0;
  for (std::size_t i = 0; i + 10 < ds.size(); i += 100) {
    const cv::Mat da = ds.loadDepth(i), db = ds.loadDepth(i + 10);
    const auto sa = gasp::segmentDepthSuperpixels(da, ds.intrinsics());
    const auto sb = gasp::segmentDepthSuperpixels(db, ds.intrinsics());
    const auto r = gasp::measureRepeatability(
        sa, sb, db, ds.intrinsics(), gasp::relativePose(*ds.frame(i + 10).T_world_camera, *ds.frame(i).T_world_camera));
    std::printf("pair %zu -> %zu: repeatability %.3f (%d in the overlap)\n", i, i + 10, r.fraction(), r.in_overlap);
    EXPECT_GE(r.fraction(), 0.5);
    sum += r.fraction();
    ++pairs;
  }
  ASSERT_EQ(pairs, 8);
  std::printf("mean repeatability over %d pairs: %.3f\n", pairs, sum / pairs);
  EXPECT_GE(sum / pairs, 0.60);
}
