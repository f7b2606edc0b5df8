// The pipeline's own parts on hand-made views: projective terms, view degeneracy, visibility.
#include <gtest/gtest.h>

#include <cmath>

#include <Eigen/Geometry>
#include <vector>

#include "gasp/core/error.h"
#include "gasp/core/undistortion.h"
#include "gasp/pipeline/depth_view.h"
#include "gasp/pipeline/projective_terms.h"
#include "gasp/pipeline/view_degeneracy.h"
#include "gasp/pipeline/visibility_check.h"

using namespace gasp;

namespace {

/// A view of a fronto-parallel wall at 2 m, one patch per 80 x 80 pixel block (hand-made
/// segmentation: the parts under test only read labels, patch normals and depth).
DepthView wallView(double z = 2.0) {
  DepthView v;
  v.projection = CameraIntrinsics::rosDefault();
  v.depth_m = cv::Mat(480, 640, CV_32FC1, cv::Scalar(static_cast<float>(z)));
  v.segmentation.labels = cv::Mat(480, 640, CV_32S);
  for (int r = 0; r < 480; ++r)
    for (int c = 0; c < 640; ++c) v.segmentation.labels.at<int>(r, c) = (r / 80) * 8 + c / 80;
  for (int id = 0; id < 48; ++id) {
    SurfacePatch p;
    p.id = id;
    const double u = (id % 8) * 80 + 39.5, vv = (id / 8) * 80 + 39.5;
    p.centroid = v.projection.unproject(u, vv, z);
    p.normal = Eigen::Vector3d(0, 0, -1);
    p.area_m2 = 0.09;
    v.segmentation.patches.push_back(p);
  }
  return v;
}

TEST(ProjectiveTerms, IdentityGivesZeroResidualTermsOnTheWall) {
  const DepthView v = wallView();
  const ProjectiveTermParams p;
  const auto terms = projectiveTerms(v, v, Isometry3::Identity(), p);
  const auto step = static_cast<std::size_t>(p.pixel_step);
  EXPECT_EQ(terms.size(), (640 / step) * (480 / step));
  for (const auto& t : terms) EXPECT_NEAR(t.n_target.dot(t.p_source - t.q_target), 0.0, 1e-9);
}

TEST(ProjectiveTerms, DistanceGateDropsFarPoints) {
  const DepthView a = wallView(2.0), b = wallView(2.2);
  EXPECT_TRUE(projectiveTerms(a, b, Isometry3::Identity()).empty());  // 0.2 m > 0.05 m gate
  ProjectiveTermParams p;
  p.max_distance_m = 0.25;
  EXPECT_FALSE(projectiveTerms(a, b, Isometry3::Identity(), p).empty());
  p.pixel_step = 0;
  EXPECT_THROW(projectiveTerms(a, b, Isometry3::Identity(), p), Error);
}

// The sample spacing in view angle sets the step where it is coarser than pixel_step: at fx 525,
// 0.873 deg is 8 pixels, 2 deg 18.3; the terms on the wall follow the step.
TEST(ProjectiveTerms, TheSampleSpacingInViewAngleSetsTheStepWhereItIsTheCoarser) {
  const DepthView v = wallView();
  ProjectiveTermParams p;
  p.pixel_step = 1;
  EXPECT_EQ(samplingStep(v.projection, p), 1);  // no spacing: pixel_step alone
  p.sample_spacing_deg = 0.873;
  EXPECT_EQ(samplingStep(v.projection, p), 8);
  p.sample_spacing_deg = 2.0;
  EXPECT_EQ(samplingStep(v.projection, p), 18);
  const auto terms = projectiveTerms(v, v, Isometry3::Identity(), p);
  EXPECT_EQ(terms.size(), static_cast<std::size_t>(((640 + 17) / 18) * ((480 + 17) / 18)));
  p.pixel_step = 24;  // the coarser of the two
  EXPECT_EQ(samplingStep(v.projection, p), 24);
  p.sample_spacing_deg = -1.0;
  EXPECT_THROW(projectiveTerms(v, v, Isometry3::Identity(), p), Error);
  p.sample_spacing_deg = 1e12;  // would overflow the step
  EXPECT_THROW(validate(p), Error);
  p.sample_spacing_deg = std::nan("");
  EXPECT_THROW(validate(p), Error);
}

TEST(ViewDegeneracy, AWallIsDegenerateACornerIsNot) {
  DepthView v = wallView();
  const auto d = analyseViewGeometry(v.segmentation);
  EXPECT_TRUE(d.degenerate);
  EXPECT_EQ(d.unobservable_directions.cols(), 3);
  // Turn a third of the patches into a floor and a third into a side wall: a corner.
  for (auto& p : v.segmentation.patches) {
    if (p.id % 3 == 1) p.normal = Eigen::Vector3d(0, -1, 0);
    if (p.id % 3 == 2) p.normal = Eigen::Vector3d(1, 0, 0);
  }
  EXPECT_FALSE(analyseViewGeometry(v.segmentation).degenerate);
  EXPECT_TRUE(analyseViewGeometry(SuperpixelSegmentation{}).degenerate);
}

TEST(VisibilityCheck, TruePosePassesAPoseInFreeSpaceFails) {
  const DepthView a = wallView(2.0);
  EXPECT_TRUE(checkVisibility(a, a, Isometry3::Identity()).passed);
  // Mapping the wall 0.5 m towards the camera puts it in space the other view saw as empty.
  Isometry3 T = Isometry3::Identity();
  T.translation() = Eigen::Vector3d(0, 0, -0.5);
  const auto c = checkVisibility(a, a, T);
  EXPECT_FALSE(c.passed);
  EXPECT_GT(c.violation_ratio, 0.9);
  EXPECT_FALSE(c.reason.empty());
  // Nothing of either view is consistent with the other at this pose: refused for too little
  // overlap before the violation limits are looked at, so not a free-space refusal (the flag the
  // odometry's scene_change.h takes for a changed scene; set by the tests below).
  EXPECT_NE(c.reason.find("consistent samples"), std::string::npos) << c.reason;
  EXPECT_FALSE(c.free_space_refused);
  // Views that do not overlap at this pose: too few consistent samples, not a free-space refusal.
  T.translation() = Eigen::Vector3d(50, 0, 0);
  const auto apart = checkVisibility(a, a, T);
  EXPECT_FALSE(apart.passed);
  EXPECT_FALSE(apart.free_space_refused) << apart.reason;
  // Nor is a pose that is not finite.
  T.translation() = Eigen::Vector3d(std::nan(""), 0, 0);
  const auto nan = checkVisibility(a, a, T);
  EXPECT_FALSE(nan.passed);
  EXPECT_FALSE(nan.free_space_refused);
  EXPECT_FALSE(checkVisibility(a, a, Isometry3::Identity()).free_space_refused);
}

TEST(VisibilityCheck, APoseThatHidesAViewBehindTheOtherFails) {
  // b sees the wall on its left 40 % and a near surface (1 m) on the rest: at the identity 60 % of
  // a's samples land behind b's surfaces. The violation limit is lifted so that only the occluded
  // share decides.
  const DepthView a = wallView(2.0);
  DepthView b = wallView(2.0);
  b.depth_m(cv::Rect(256, 0, 384, 480)).setTo(1.0f);
  VisibilityCheckParams p;
  p.max_violation_ratio = 1.0;
  p.max_occluded_ratio = 1.0;
  const auto loose = checkVisibility(a, b, Isometry3::Identity(), p);
  EXPECT_TRUE(loose.passed) << loose.reason;
  EXPECT_NEAR(loose.occluded_ratio, 0.6, 0.02);
  p.max_occluded_ratio = 0.5;
  const auto strict = checkVisibility(a, b, Isometry3::Identity(), p);
  EXPECT_FALSE(strict.passed);
  EXPECT_NE(strict.reason.find("behind"), std::string::npos) << strict.reason;
  EXPECT_TRUE(strict.free_space_refused);
  // The true pose of one view against itself has nothing occluded.
  EXPECT_EQ(checkVisibility(a, a, Isometry3::Identity()).occluded_ratio, 0.0);
  p.max_occluded_ratio = 1.5;
  EXPECT_THROW(checkVisibility(a, b, Isometry3::Identity(), p), Error);
}

TEST(VisibilityCheck, AnObjectSeenByOneViewIsAllowedViolationsFromBothViewsAreNot) {
  // The wall at 2 m, a box at 1 m in front of it: a box that appears in b alone violates one
  // direction only (b's box samples lie in space a saw as empty; a's wall behind it is occluded),
  // a box that moved between the views violates both (each view's box lies where the other saw
  // the wall), and so does a wrong alignment of look-alike structure.
  const auto withBox = [](const cv::Rect& box) {
    DepthView v = wallView(2.0);
    v.depth_m(box).setTo(1.0f);
    return v;
  };
  const DepthView wall = wallView(2.0);
  const cv::Rect left(80, 160, 128, 192), right(432, 160, 128, 192);  // 8 % of the image each
  const auto appears = checkVisibility(wall, withBox(right), Isometry3::Identity());
  EXPECT_TRUE(appears.passed) << appears.reason;
  EXPECT_NEAR(appears.violation_ratio, 0.08, 0.01);
  EXPECT_EQ(appears.violation_ratio_lesser, 0.0);
  const auto moved = checkVisibility(withBox(left), withBox(right), Isometry3::Identity());
  EXPECT_FALSE(moved.passed);
  EXPECT_NEAR(moved.violation_ratio_lesser, 0.08, 0.01);
  EXPECT_NE(moved.reason.find("seen from both views"), std::string::npos) << moved.reason;
  EXPECT_TRUE(moved.free_space_refused);
  // Below the two-way limit, or with the limit lifted, the moved box is allowed.
  const cv::Rect small_left(80, 160, 64, 96), small_right(432, 160, 64, 96);  // 2 % each
  const auto small = checkVisibility(withBox(small_left), withBox(small_right), Isometry3::Identity());
  EXPECT_TRUE(small.passed) << small.reason;
  EXPECT_NEAR(small.violation_ratio_lesser, 0.02, 0.005);
  VisibilityCheckParams p;
  p.max_two_way_violation_ratio = 1.0;
  EXPECT_TRUE(checkVisibility(withBox(left), withBox(right), Isometry3::Identity(), p).passed);
  p.max_two_way_violation_ratio = -0.1;
  EXPECT_THROW(checkVisibility(wall, wall, Isometry3::Identity(), p), Error);
}

TEST(VisibilityCheck, TheLargestConnectedRegionOfViolationsIsMeasured) {
  // The share of a direction's violating samples in its largest 8-connected region on the 8-px
  // sampling grid (a diagnostic: docs/pipeline.md, "Violations seen from both views"). One moved
  // box: all of them; two boxes of 3 : 1 area in one view: 0.75 there; single violating samples
  // on every other grid point (none touching another, not even at a corner): 1 / their number.
  // The check keeps the smaller and the larger of the two directions' shares.
  const auto withBoxes = [](const std::vector<cv::Rect>& boxes) {
    DepthView v = wallView(2.0);
    for (const auto& b : boxes) v.depth_m(b).setTo(1.0f);
    return v;
  };
  const DepthView wall = wallView(2.0);
  EXPECT_EQ(checkVisibility(wall, wall, Isometry3::Identity()).violation_blob_share_lesser, 1.0);  // no violation
  const cv::Rect left(80, 160, 128, 192), right(432, 160, 128, 192);
  const auto one = checkVisibility(withBoxes({left}), withBoxes({right}), Isometry3::Identity());
  EXPECT_DOUBLE_EQ(one.violation_blob_share_lesser, 1.0);
  EXPECT_DOUBLE_EQ(one.violation_blob_share, 1.0);
  const auto two = checkVisibility(withBoxes({cv::Rect(80, 80, 96, 128), cv::Rect(80, 320, 32, 128)}),
                                   withBoxes({right}), Isometry3::Identity());
  EXPECT_DOUBLE_EQ(two.violation_blob_share_lesser, 0.75);
  EXPECT_DOUBLE_EQ(two.violation_blob_share, 1.0);
  DepthView specks = wallView(2.0);
  int n = 0;
  for (int v = 0; v < specks.depth_m.rows; v += 16)
    for (int u = 0; u < specks.depth_m.cols; u += 16) specks.depth_m.at<float>(v, u) = 1.0f, ++n;
  // The 8 x 12 specks inside the other view's box agree with it; the rest violate, one by one.
  const auto scattered = checkVisibility(specks, withBoxes({right}), Isometry3::Identity());
  EXPECT_DOUBLE_EQ(scattered.violation_blob_share_lesser, 1.0 / (n - 8 * 12));
  EXPECT_DOUBLE_EQ(scattered.violation_blob_share, 1.0);
}

}  // namespace

TEST(DepthViewUndistortion, ADistortedCameraGivesAPinholeView) {
  // A fronto-parallel wall at 2 m through fr1's lens (depth as the distorted camera stores it is
  // still 2 m everywhere: depth along the optical axis of a fronto-parallel plane). The view holds
  // the resampled depth and the pinhole intrinsics; a camera without distortion is left alone.
  const auto k = CameraIntrinsics::tumFreiburg1();
  cv::Mat depth(k.height, k.width, CV_32FC1, cv::Scalar(2.0f));
  depth(cv::Rect(0, 0, 40, 40)).setTo(1.0f);  // a corner object: moves under undistortion
  const DepthView v = makeDepthView(depth, k);
  for (double c : v.projection.pinhole().distortion) EXPECT_EQ(c, 0.0);
  EXPECT_EQ(v.projection.pinhole().fx, k.fx);
  const cv::Mat expected = Undistortion(k).applyToDepth(depth);
  EXPECT_EQ(cv::norm(v.depth_m, expected, cv::NORM_INF), 0.0);
  EXPECT_GT(cv::norm(v.depth_m, depth, cv::NORM_INF), 0.0);
  EXPECT_FALSE(v.segmentation.patches.empty());
  const auto k3 = CameraIntrinsics::tumFreiburg3();
  cv::Mat depth3(k3.height, k3.width, CV_32FC1, cv::Scalar(2.0f));
  const DepthView v3 = makeDepthView(depth3, k3);
  EXPECT_EQ(v3.depth_m.data, depth3.data);  // not resampled
  // The shared maps are reused for equal intrinsics.
  EXPECT_EQ(sharedUndistortion(k).get(), sharedUndistortion(k).get());
}
