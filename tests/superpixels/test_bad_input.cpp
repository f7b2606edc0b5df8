// Bad input gives a clear error or an empty, valid result -- never a crash or a hang.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "gasp/core/error.h"
#include "gasp/superpixels/depth_superpixels.h"
#include "segmentation_checks.h"

namespace {
const gasp::CameraIntrinsics kCamera = gasp::CameraIntrinsics::rosDefault();
}

TEST(SuperpixelsBadInput, NoValidDepthGivesAnEmptyResult) {
  for (float fill : {0.0f, std::numeric_limits<float>::quiet_NaN(), -1.0f,
                     std::numeric_limits<float>::infinity()}) {
    const cv::Mat depth(480, 640, CV_32FC1, cv::Scalar(fill));
    const auto seg = gasp::segmentDepthSuperpixels(depth, kCamera);
    EXPECT_TRUE(seg.patches.empty());
    EXPECT_EQ(seg.stats.valid_pixels, 0u);
    EXPECT_EQ(seg.stats.coverage(), 0.0);
    EXPECT_EQ(cv::countNonZero(seg.labels != -1), 0);
  }
}

TEST(SuperpixelsBadInput, ASingleValidPixelIsNoPatch) {
  cv::Mat depth(480, 640, CV_32FC1, cv::Scalar(0.0f));
  depth.at<float>(200, 300) = 1.5f;
  const auto seg = gasp::segmentDepthSuperpixels(depth, kCamera);
  EXPECT_TRUE(seg.patches.empty());
  EXPECT_EQ(seg.stats.valid_pixels, 1u);
  EXPECT_EQ(seg.stats.dropped_pixels, 1u);
}

TEST(SuperpixelsBadInput, OnePlaneIsSegmentedNormally) {
  const cv::Mat depth(480, 640, CV_32FC1, cv::Scalar(2.0f));
  const auto seg = gasp::segmentDepthSuperpixels(depth, kCamera);
  EXPECT_GT(seg.patches.size(), 50u);
  EXPECT_DOUBLE_EQ(seg.stats.coverage(), 1.0);
  for (const auto& p : seg.patches) EXPECT_GT(-p.normal.z(), 0.999);
}

TEST(SuperpixelsBadInput, WrongTypeOrSizeThrows) {
  EXPECT_THROW(gasp::segmentDepthSuperpixels(cv::Mat(480, 640, CV_16UC1, cv::Scalar(1000)), kCamera), gasp::Error);
  EXPECT_THROW(gasp::segmentDepthSuperpixels(cv::Mat(240, 320, CV_32FC1, cv::Scalar(1.0f)), kCamera), gasp::Error);
  EXPECT_THROW(gasp::segmentDepthSuperpixels(cv::Mat(), kCamera), gasp::Error);
}

TEST(SuperpixelsBadInput, InvalidParametersThrow) {
  const cv::Mat depth(480, 640, CV_32FC1, cv::Scalar(2.0f));
  gasp::SuperpixelParams p;
  p.target_patch_area_m2 = 0.0;
  EXPECT_THROW(gasp::segmentDepthSuperpixels(depth, kCamera, p), gasp::Error);
  p = {};
  p.surfaces.normal_min_radius_px = 0;
  EXPECT_THROW(gasp::segmentDepthSuperpixels(depth, kCamera, p), gasp::Error);
  for (int step : {0, 5}) {
    p = {};
    p.processing_step_px = step;
    EXPECT_THROW(gasp::segmentDepthSuperpixels(depth, kCamera, p), gasp::Error) << step;
  }
  p = {};
  p.kmeans.kmeans_iteration_step_px = 0;
  EXPECT_THROW(gasp::segmentDepthSuperpixels(depth, kCamera, p), gasp::Error);
  p = {};
  p.kmeans.kmeans_coarse_iterations = -1;
  EXPECT_THROW(gasp::segmentDepthSuperpixels(depth, kCamera, p), gasp::Error);
  p = {};
  p.borders.crease_band_px = -1;
  EXPECT_THROW(gasp::segmentDepthSuperpixels(depth, kCamera, p), gasp::Error);
  p = {};
  p.borders.crease_min_angle_deg = 0.0;
  EXPECT_THROW(gasp::segmentDepthSuperpixels(depth, kCamera, p), gasp::Error);
  p = {};
  p.borders.plane_noise_abs_m = 0.0;
  p.borders.plane_noise_rel = 0.0;
  EXPECT_THROW(gasp::segmentDepthSuperpixels(depth, kCamera, p), gasp::Error);
  for (double bad : {-1.0, std::nan("")}) {
    p = {};
    p.borders.step_min_sigmas = bad;
    EXPECT_THROW(gasp::segmentDepthSuperpixels(depth, kCamera, p), gasp::Error);
    p = {};
    p.borders.step_smoothness = bad;
    EXPECT_THROW(gasp::segmentDepthSuperpixels(depth, kCamera, p), gasp::Error);
  }
}

TEST(SuperpixelsBadInput, SparseSpecklesDoNotHang) {
  cv::Mat depth(480, 640, CV_32FC1, cv::Scalar(0.0f));
  for (int v = 0; v < 480; v += 3)
    for (int u = 0; u < 640; u += 3) depth.at<float>(v, u) = 1.0f + 0.001f * static_cast<float>((u * 7 + v * 13) % 100);
  const auto seg = gasp::segmentDepthSuperpixels(depth, kCamera);
  EXPECT_TRUE(seg.patches.empty());  // isolated pixels: no surface
  EXPECT_EQ(seg.stats.dropped_pixels, seg.stats.valid_pixels);
}

TEST(SuperpixelsBadInput, TheStepBordersTakeTheSameInput) {
  gasp::SuperpixelParams p;
  p.borders.step_borders = true;
  for (float fill : {0.0f, std::numeric_limits<float>::quiet_NaN()}) {
    const auto seg = gasp::segmentDepthSuperpixels(cv::Mat(480, 640, CV_32FC1, cv::Scalar(fill)), kCamera, p);
    EXPECT_TRUE(seg.patches.empty());
  }
  cv::Mat single(480, 640, CV_32FC1, cv::Scalar(0.0f));
  single.at<float>(200, 300) = 1.5f;
  EXPECT_TRUE(gasp::segmentDepthSuperpixels(single, kCamera, p).patches.empty());
  const auto plane = gasp::segmentDepthSuperpixels(cv::Mat(480, 640, CV_32FC1, cv::Scalar(2.0f)), kCamera, p);
  EXPECT_GT(plane.patches.size(), 50u);
  EXPECT_DOUBLE_EQ(plane.stats.coverage(), 1.0);
  // A step across the whole image (two fronto-parallel half planes 3 cm apart at 2 m, exact
  // depth, below a depth discontinuity there): every pixel in a contiguous patch. (Not yet: every
  // patch on one side -- about 30 of ~1100 straddle the step, see docs/superpixels.md.)
  cv::Mat step(480, 640, CV_32FC1, cv::Scalar(2.0f));
  step.colRange(320, 640).setTo(2.03f);
  const auto seg = gasp::segmentDepthSuperpixels(step, kCamera, p);
  EXPECT_DOUBLE_EQ(seg.stats.coverage(), 1.0);
  EXPECT_EQ(gasp::test::countNonContiguousPatches(seg), 0);
}
