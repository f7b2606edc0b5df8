// The pair pipeline on real fr1_xyz pairs at a wide baseline (50 frames apart), where the mutual
// associations are too few: the one-way fallback finds the right pose on 400 -> 430, and the
// visibility check declines the wrong one of 650 -> 700 (with the images undistorted: 2.4 m /
// 154 deg off, 7 % violations but 79 % of the samples behind the other view's surfaces).
// Skipped without ../shared/data.
#include <gtest/gtest.h>

#include <cmath>

#include "gasp/core/camera_roll.h"
#include "gasp/core/tum_dataset.h"
#include "gasp/pipeline/pair_registration.h"
#include "gasp_test_data.h"

namespace {

using namespace gasp;

struct RealPair {
  DepthView a, b;
  Isometry3 T_b_a;
};

RealPair load(const std::string& dir, std::size_t i, std::size_t j, const SuperpixelParams& sp = {}) {
  const auto ds = TumDataset::open(dir);
  auto [a, b] = makeDepthViews(ds.loadDepth(i), ds.loadDepth(j), ds.intrinsics(), sp);
  return {std::move(a), std::move(b), relativePose(*ds.frame(j).T_world_camera, *ds.frame(i).T_world_camera)};
}

/// Translation error of a result's pose against the pair's reference [m].
double translationError(const RealPair& p, const PairResult& r) {
  return translationNorm(p.T_b_a.inverse() * r.pose.T_target_source);
}

/// Rotation error of a result's pose against the pair's reference [deg].
double rotationErrorDeg(const RealPair& p, const PairResult& r) {
  return rotationAngle(p.T_b_a.inverse() * r.pose.T_target_source) * 180.0 / M_PI;
}

/// The defaults without the finer-scale retry: what the default scale alone does.
PairParams defaultScaleOnly() {
  PairParams params;
  params.retry.finer_area_factor = 0.0;
  return params;
}

/// A claimed pose must be right (within 10 cm); a declined one must give `why` in its reason.
/// Returns whether the pose was declined.
bool expectRightOrDeclined(const RealPair& p, const PairResult& r, const char* why) {
  if (r.pose.success) {
    EXPECT_LT(translationError(p, r), 0.1) << "a wrong pose was claimed";
    return false;
  }
  EXPECT_NE(r.pose.reason.find(why), std::string::npos) << r.pose.reason;
  return true;
}

TEST(RealPairs, OneWayFallbackFindsTheWideBaselinePose) {
  GASP_REQUIRE_DATA(dir, "tum/fr1_xyz");
  const RealPair p = load(dir, 400, 430);
  const PairResult r = registerViews(p.a, p.b);
  ASSERT_TRUE(r.pose.success) << r.pose.reason;
  EXPECT_TRUE(r.used_one_way);
  EXPECT_GE(r.guided_support, PairParams{}.hypothesise.guided.min_support);
  EXPECT_LT(translationError(p, r), 0.05);
  EXPECT_LT(rotationErrorDeg(p, r), 3.0);
  // Without the fallback (and the finer-scale retry) the mutual associations alone give no
  // estimate here.
  PairParams no_fallback = defaultScaleOnly();
  no_fallback.retry.one_way_fallback = false;
  EXPECT_FALSE(registerViews(p.a, p.b, no_fallback).pose.success);
}

TEST(RealPairs, FinerScaleRetryRegistersASmallOverlap) {
  // 540 -> 590 (0.48 m, 8 deg): about 60 of the source's 310 patches lie in the overlap, too few
  // for a consensus at the default patch size, mutual or one-way. The retry at 0.3 x the area
  // finds the pose with mutual associations.
  GASP_REQUIRE_DATA(dir, "tum/fr1_xyz");
  const RealPair p = load(dir, 540, 590);
  EXPECT_FALSE(registerViews(p.a, p.b, defaultScaleOnly()).pose.success);
  const PairResult r = registerViews(p.a, p.b);
  ASSERT_TRUE(r.pose.success) << r.pose.reason;
  EXPECT_NE(r.retry_views, nullptr);
  EXPECT_FALSE(r.used_one_way);
  EXPECT_LT(translationError(p, r), 0.05);
  EXPECT_LT(rotationErrorDeg(p, r), 2.0);
}

TEST(RealPairs, AnUnobservableDenseProblemIsRetriedAndDeclined) {
  // 600 -> 650 (0.50 m / 14 deg, 25 of 596 source patches in the overlap): the default scale's
  // dense problem is unobservable at RANSAC's pose (9 inliers) although both views fix every
  // direction: the structure that fixes them is not aligned, no partial pose. That may be a wrong
  // pose's, so the finer-scale retry runs (fr1_xyz 540 -> 590 with the rolling-shutter deskew is
  // registered that way, docs/pipeline.md step 6); here it finds no consensus either: no
  // estimate, with the default scale's reason first.
  GASP_REQUIRE_DATA(dir, "tum/fr1_xyz");
  const RealPair p = load(dir, 600, 650);
  const PairResult r = registerViews(p.a, p.b);
  if (expectRightOrDeclined(p, r, "x the patch area: ")) {
    EXPECT_TRUE(r.retried);
    EXPECT_TRUE(r.pose.degenerate);
    EXPECT_TRUE(r.dense_unobservable);
    EXPECT_EQ(r.pose.reason.rfind("unobservable: ", 0), 0u) << r.pose.reason;
    EXPECT_NE(r.pose.reason.find("the views' own geometry fixes"), std::string::npos) << r.pose.reason;
  }
}

TEST(RealPairs, FinerScaleRetryClaimsNoWrongPoseOnATinyOverlap) {
  // 200 -> 250 (0.58 m / 23 deg, 21 of 337 source patches in the overlap): segmented at 13 or
  // 10 cm^2 it gets poses 3.6-9 cm / 3.3-4.5 deg off, at 15 cm^2 with one-way partners 0.35 m /
  // 23 deg off (docs/pipeline.md). With the defaults: right or declined.
  GASP_REQUIRE_DATA(dir, "tum/fr1_xyz");
  const RealPair p = load(dir, 200, 250);
  const PairResult r = registerViews(p.a, p.b);
  if (!expectRightOrDeclined(p, r, "x the patch area: ")) {
    EXPECT_LT(rotationErrorDeg(p, r), 3.0);
  }
}

TEST(RealPairs, AWrongFallbackPoseIsDeclined) {
  GASP_REQUIRE_DATA(dir, "tum/fr1_xyz");
  const RealPair p = load(dir, 650, 700);
  const PairParams no_retry = defaultScaleOnly();  // the finer-scale retry finds nothing either
  const PairResult r = registerViews(p.a, p.b, no_retry);
  if (expectRightOrDeclined(p, r, "behind")) {
    EXPECT_TRUE(r.used_one_way);
  }
  // Without the limit on occluded samples the wrong pose is claimed: that limit declines it.
  PairParams loose = no_retry;
  loose.certify.visibility.max_occluded_ratio = 1.0;
  const PairResult w = registerViews(p.a, p.b, loose);
  ASSERT_TRUE(w.pose.success);
  EXPECT_GT(translationError(p, w), 0.5);
}

TEST(RealPairs, TheFallbackViolationLimitDeclinesAWrongPose) {
  // 280 -> 310 segmented with the step borders: the mutual associations give no pose, the
  // one-way ones a pose 0.20 m / 14 deg off with 14 % violations (right fallback poses of the
  // benchmark: at most 3.4 %).
  GASP_REQUIRE_DATA(dir, "tum/fr1_xyz");
  SuperpixelParams sp;
  sp.borders.step_borders = true;
  const RealPair p = load(dir, 280, 310, sp);
  // The default scale only (the finer-scale retry registers this pair, see below).
  const PairParams no_retry = defaultScaleOnly();
  EXPECT_TRUE(expectRightOrDeclined(p, registerViews(p.a, p.b, no_retry), "empty"));
  const PairResult retried = registerViews(p.a, p.b);
  EXPECT_TRUE(retried.retried);
  expectRightOrDeclined(p, retried, "x the patch area");
  PairParams loose = no_retry;
  loose.certify.fallback_max_violation_ratio = 0.15;  // the limit before
  // Its violations are seen from both views as well: the two-way limit declines it by itself.
  EXPECT_TRUE(expectRightOrDeclined(p, registerViews(p.a, p.b, loose), "seen from both views"));
  loose.certify.visibility.max_two_way_violation_ratio = 1.0;  // the check before that too
  // The fallback pose's patch problem is degenerate: the slide scan moves the loosened claim to
  // where the views agree more (2 cm / 1.2 deg from the reference).
  const PairResult moved = registerViews(p.a, p.b, loose);
  ASSERT_TRUE(moved.pose.success) << moved.pose.reason;
  EXPECT_TRUE(moved.slide.moved) << moved.slide.summary();
  EXPECT_LT(translationError(p, moved), 0.05);
  EXPECT_LT(rotationErrorDeg(p, moved), 3.0);
  // Without the scan the limit alone stands between the wrong pose and the caller.
  loose.refine.slide_scan.enabled = false;
  const PairResult w = registerViews(p.a, p.b, loose);
  ASSERT_TRUE(w.pose.success) << w.pose.reason;
  EXPECT_TRUE(w.used_one_way);
  EXPECT_GT(translationError(p, w), 0.1);
}

TEST(RealPairs, WideEdgeGatesStopTheCabinetSlide) {
  // fr3_cabinet_kf keyframes 8 -> 10 (about 40 frames): views of the floor and the cabinet top.
  // Segmented without the crease borders (superpixel_params.h), the patch pose is ~13 cm off along
  // the cabinet top; pixel terms cannot move it and edge terms within the pixel gates find no
  // partner (paired share below wide_edge_min_paired_share). The second refinement with wider
  // edge gates does, and its pose is the one whose views agree more. (With the crease borders,
  // the default, the cabinet's edges are cut where its faces meet and the first refinement does
  // not slide: checked last.)
  GASP_REQUIRE_DATA(dir, "tum/fr3_cabinet_kf");
  SuperpixelParams no_crease;
  no_crease.borders.crease_borders = false;
  const RealPair p = load(dir, 8, 10, no_crease);
  const PairResult r = registerViews(p.a, p.b);
  ASSERT_TRUE(r.pose.success) << r.pose.reason;
  EXPECT_TRUE(r.wide_edge_pose);
  EXPECT_GE(r.edge_paired_share, 0.0);
  EXPECT_LT(r.edge_paired_share, PairParams{}.refine.edges.wide_min_paired_share);
  EXPECT_LT(translationError(p, r), 0.05);
  PairParams narrow;
  narrow.refine.edges.wide_gate_factor = 0.0;
  // With the former dense rounds (8, plain); the extrapolated rounds take the narrow pose to
  // 3.2 cm (docs/pipeline.md, "Extrapolated rounds").
  narrow.refine.dense.max_rounds = 8;
  narrow.refine.dense.extrapolation_max = 0.0;
  narrow.retry.finer_area_factor = 0.0;
  // The slid pose violates the other view's free space from both views (10 % and 7 %): the
  // two-way limit declines it as well. Without that limit the certificate's uniqueness test
  // declines it (RANSAC's distinct alternative explains the views about as well); without both it
  // is claimed.
  EXPECT_TRUE(expectRightOrDeclined(p, registerViews(p.a, p.b, narrow), "seen from both views"));
  narrow.certify.visibility.max_two_way_violation_ratio = 1.0;
  EXPECT_TRUE(expectRightOrDeclined(p, registerViews(p.a, p.b, narrow), "not unique"));
  narrow.certify.min_likelihood_ratio = 0.0;
  const PairResult n = registerViews(p.a, p.b, narrow);
  ASSERT_TRUE(n.pose.success) << n.pose.reason;
  EXPECT_FALSE(n.wide_edge_pose);
  EXPECT_GT(translationError(p, n), 0.08);

  const RealPair d = load(dir, 8, 10);
  const PairResult c = registerViews(d.a, d.b, narrow);
  ASSERT_TRUE(c.pose.success) << c.pose.reason;
  EXPECT_LT(translationError(d, c), 0.05);
}

TEST(RealPairs, ViolationsSeenFromBothViewsDeclineALookAlikeAlignment) {
  // fr3_cabinet_kf keyframes 12 -> 18 (about 120 frames): the camera orbits the cabinet by 46 deg
  // and 1.0 m. The associations give a pose as if it had hardly moved (0.96 m / 46 deg off):
  // floor onto floor, one face of the cabinet onto another. It violates the other view's free
  // space by 14 %, under the one-direction limit (15 %, which an object that appears between the
  // views may take), but by 8 % from the other view as well, which no such object explains
  // (right poses of the benchmarks: at most 2.9 %; docs/pipeline.md "Violations seen from both
  // views"). Declined at the default scale, the pair goes to the finer-scale retry, whose
  // pose is right.
  GASP_REQUIRE_DATA(dir, "tum/fr3_cabinet_kf");
  const RealPair p = load(dir, 12, 18);
  EXPECT_TRUE(expectRightOrDeclined(p, registerViews(p.a, p.b, defaultScaleOnly()), "seen from both views"));
  const PairResult retried = registerViews(p.a, p.b);
  ASSERT_TRUE(retried.pose.success) << retried.pose.reason;
  EXPECT_TRUE(retried.retried);
  EXPECT_LT(translationError(p, retried), 0.05);
  EXPECT_LT(rotationErrorDeg(p, retried), 2.0);
  PairParams loose = defaultScaleOnly();
  loose.certify.visibility.max_two_way_violation_ratio = 1.0;  // the check before
  loose.certify.min_likelihood_ratio = 0.0;                     // and no uniqueness test (below)
  const PairResult w = registerViews(p.a, p.b, loose);
  ASSERT_TRUE(w.pose.success) << w.pose.reason;
  EXPECT_GT(translationError(p, w), 0.5);
  EXPECT_GT(w.visibility.violation_ratio_lesser, PairParams{}.certify.visibility.max_two_way_violation_ratio);
  EXPECT_LT(w.visibility.violation_ratio, PairParams{}.certify.visibility.max_violation_ratio);
  // The certificate's uniqueness test declines the look-alike as well: RANSAC's distinct
  // alternative explains the views about as well (certify_stage.h).
  loose.certify.min_likelihood_ratio = PairParams{}.certify.min_likelihood_ratio;
  const PairResult u = registerViews(p.a, p.b, loose);
  EXPECT_TRUE(expectRightOrDeclined(p, u, "not unique"));
}

TEST(RealPairs, ARolledCabinetPairNeedsMoreThanEightRounds) {
  // fr3_cabinet_kf keyframes 10 -> 12 with the target view turned by 180 deg (the camera rolled
  // about its optical axis; docs/benchmarks.md "Camera roll on real data"). The patch pose rests
  // on 11 RANSAC inliers and is 14 cm / 8 deg off. Eight plain rounds (the former limit) stopped
  // 5.4 cm / 3.3 deg off, a claimed pose. Without the line search, 16 rounds swing about the
  // reference with steps of several centimetres and stop at the limit, still moving
  // (docs/pipeline.md "Extrapolated rounds"). With it (the default), a step that scores worse
  // where it lands is shortened or refused, and the rounds end before the limit where the
  // upright pair ends (0.9 cm / 1.0 deg from the reference).
  GASP_REQUIRE_DATA(dir, "tum/fr3_cabinet_kf");
  const auto ds = TumDataset::open(dir);
  const int turn = 180;
  const RealPair p{makeDepthView(ds.loadDepth(10), ds.intrinsics()),
                   makeDepthView(turnImage(ds.loadDepth(12), turn), turnIntrinsics(ds.intrinsics(), turn)),
                   turnRotation(turn) * relativePose(*ds.frame(12).T_world_camera, *ds.frame(10).T_world_camera)};
  const PairParams defaults;
  const PairResult r = registerViews(p.a, p.b);
  ASSERT_TRUE(r.pose.success) << r.pose.reason;
  EXPECT_LT(translationError(p, r), 0.015);
  EXPECT_LT(rotationErrorDeg(p, r), 1.2);
  EXPECT_LT(r.dense_rounds_run, defaults.refine.dense.max_rounds);
  EXPECT_TRUE(r.dense_line_search_stopped || r.dense_last_step_m < defaults.refine.dense.converged_m)
      << "last step " << r.dense_last_step_m;

  PairParams no_search;
  no_search.refine.dense.line_search = false;
  const PairResult swinging = registerViews(p.a, p.b, no_search);
  ASSERT_TRUE(swinging.pose.success) << swinging.pose.reason;
  EXPECT_EQ(swinging.dense_rounds_run, defaults.refine.dense.max_rounds);
  EXPECT_GT(swinging.dense_last_step_m, defaults.refine.dense.converged_m);
  EXPECT_EQ(swinging.dense_steps_shortened, 0);
  EXPECT_FALSE(swinging.dense_line_search_stopped);

  PairParams eight = no_search;
  eight.refine.dense.extrapolation_max = 0.0;
  eight.refine.dense.max_rounds = 8;
  const PairResult short_of = registerViews(p.a, p.b, eight);
  ASSERT_TRUE(short_of.pose.success) << short_of.pose.reason;
  EXPECT_GT(translationError(p, short_of), 0.04);
  EXPECT_EQ(short_of.dense_rounds_run, 8);
}

}  // namespace
