// End-to-end pairs on the simulator (Kinect noise on): wide baseline, 180-degree roll, occluder,
// partial overlap, repeated objects must give the true pose within 2 cm / 1 deg; degenerate
// scenes must be flagged; bad input must give no estimate with a reason.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <memory>

#include "gasp/association/association_quality.h"
#include "gasp/core/error.h"
#include "gasp/eval/pose_consistency.h"
#include "gasp/pipeline/pair_registration.h"
#include "gasp/registration/partial_pose.h"
#include "gasp/sim/simulation.h"
#include "synthetic_pairs.h"

using namespace gasp;

namespace {

using test::makePair;
using test::Pair;
using test::simulation;

struct Case {
  const char* scene;
  int from, to;
  const char* what;
};

class SyntheticPair : public ::testing::TestWithParam<Case> {};

TEST_P(SyntheticPair, RecoversTheTruePose) {
  const Case c = GetParam();
  const Pair p = makePair(c.scene, c.from, c.to);
  const PairResult r = registerViews(p.a, p.b);
  ASSERT_TRUE(r.pose.success) << c.what << ": " << r.pose.reason;
  const Isometry3 E = p.T_b_a.inverse() * r.pose.T_target_source;
  EXPECT_LT(translationNorm(E), 0.02) << c.what;
  EXPECT_LT(rotationAngle(E) * 180.0 / M_PI, 1.0) << c.what;
  EXPECT_FALSE(r.pose.degenerate);
  EXPECT_GE(r.pose.num_inliers, 8);
  // The information matrix is a proper one: symmetric positive definite.
  EXPECT_TRUE(r.pose.information.isApprox(r.pose.information.transpose(), 1e-9));
  EXPECT_GT(r.pose.information_eigenvalues.minCoeff(), 0.0);
  // The edge information is the refinement's with the default model error, and the true error is
  // plausible under it: NEES within the chi-square (6) 99.9 % quantile. The bound catches an edge
  // information that is too certain, not one that is too cautious. (The refinement's own
  // information gave a median NEES of 8-33 and up to 650 on the synthetic benchmark pairs:
  // docs/pipeline.md, "How far the information can be trusted".)
  EXPECT_EQ(r.edge_information, informationWithModelError(r.pose.information, ModelError{}));
  const double nees = eval::nees(r.pose.T_target_source, p.T_b_a, r.edge_information);
  std::printf("%s: NEES %.2f under the edge information, %.2f under the refinement's\n", c.what, nees,
              eval::nees(r.pose.T_target_source, p.T_b_a, r.pose.information));
  EXPECT_LT(nees, 22.46) << c.what;
  EXPECT_TRUE(r.visibility.passed);
  // The verified (guided) associations at the final pose, scored by association_quality.h's
  // definition: precision >= 0.95 and density >= 0.5 (issue 4's target for synthetic pairs;
  // measured 0.996-1.000 and 0.81-0.87 on the room pairs).
  const AssociationQuality q =
      evaluateAssociations(r.verified, p.a.segmentation, p.b.segmentation, p.b.depth_m, p.b.projection.pinhole(), p.T_b_a);
  std::printf("%s: %zu associations, %zu verified, verified precision %.3f, density %.3f, support %d, one-way %d\n",
              c.what, r.association.associations.size(), r.verified.size(), q.precision(), q.density(),
              r.guided_support, int(r.used_one_way));
  EXPECT_GE(q.precision(), 0.95) << c.what;
  EXPECT_GE(q.density(), 0.5) << c.what;
}

// Motions (ground truth): room 3->9 0.59 m / 12 deg; 44->59 180-degree roll; 33->36 an occluder
// appears; 18->24 partial overlap (19 deg pan); repeated boxes 0->3 and 18->21.
INSTANTIATE_TEST_SUITE_P(Simulator, SyntheticPair,
                         ::testing::Values(Case{"room", 3, 9, "wide baseline"}, Case{"room", 44, 59, "180-degree roll"},
                                           Case{"room", 33, 36, "occluder appears"},
                                           Case{"room", 18, 24, "partial overlap"},
                                           Case{"repeated", 0, 3, "repeated objects"},
                                           Case{"repeated", 18, 21, "repeated objects, pan"}));

TEST(DegenerateScene, OnePlaneIsFlagged) {
  const Pair p = makePair("plane", 0, 2);
  const PairResult r = registerViews(p.a, p.b);
  EXPECT_FALSE(r.pose.success);
  EXPECT_TRUE(r.pose.degenerate);
  EXPECT_NE(r.pose.reason.find("translation along"), std::string::npos) << r.pose.reason;
  EXPECT_NE(r.pose.reason.find("rotation about"), std::string::npos) << r.pose.reason;
}

TEST(DegenerateScene, CorridorOfParallelPlanesIsFlagged) {
  for (int i : {0, 30}) {
    const Pair p = makePair("corridor", i, i + 2);
    const PairResult r = registerViews(p.a, p.b);
    EXPECT_FALSE(r.pose.success) << "frame " << i;
    EXPECT_TRUE(r.pose.degenerate) << "frame " << i << ": " << r.pose.reason;
    EXPECT_NE(r.pose.reason.find("translation along"), std::string::npos) << r.pose.reason;
  }
}

// The plane-dominated scenes under a hand-held camera (issue 46, docs/simulator.md), every pair
// 5, 10 and 20 frames apart from every 5th frame of their 60: a full pose is never beyond 5 cm /
// 2 deg of the exact truth, nor a partial pose in its observed directions; a partial pose has one
// to three free directions, each with zero information for a pose graph and positive information
// elsewhere; where the objects fix every direction (floor_6) every pair gets a full pose, and on
// the bare floor every pair gets a partial one.
TEST(PlaneDominatedScenes, NoClaimedPoseIsWrong) {
  for (const std::string scene : {"floor_0", "floor_1", "floor_3", "floor_6", "wall_door", "corridor_walk", "table_top"}) {
    int pairs = 0, full = 0, partial = 0;
    const auto& sim = simulation(scene);
    const auto K = sim::SimulationOptions{}.intrinsics;
    std::map<int, DepthView> views;  // each frame segmented once
    const auto view = [&](int k) -> const DepthView& {
      auto it = views.find(k);
      if (it == views.end()) it = views.emplace(k, makeDepthView(sim.frame(k).depth, K)).first;
      return it->second;
    };
    for (int skip : {5, 10, 20})
      for (int i = 0; i + skip < sim.size(); i += 5) {
        const Pair p{view(i), view(i + skip), relativePose(sim.frame(i + skip).T_world_camera, sim.frame(i).T_world_camera)};
        const PairResult r = registerViews(p.a, p.b);
        const std::string what = scene + " " + std::to_string(i) + "->" + std::to_string(i + skip) + ": " + r.pose.reason;
        ++pairs;
        if (r.pose.partial) {
          ++partial;
          EXPECT_FALSE(r.pose.success) << what;
          const auto free = r.pose.unobservable_directions.cols();
          EXPECT_GE(free, 1) << what;
          EXPECT_LE(free, kMaxFreeDirections) << what;
          const ObservedError e = observedError(r.pose, p.T_b_a);
          EXPECT_LE(e.translation_m, 0.05) << what;
          EXPECT_LE(e.rotation_deg, 2.0) << what;
          const auto twists = unobservableTwists(r.pose);
          const double scale = r.edge_information.norm();
          EXPECT_GT(scale, 0.0) << what;
          for (Eigen::Index k = 0; k < twists.cols(); ++k)
            EXPECT_LE((r.edge_information * twists.col(k)).norm(), 1e-9 * scale) << what;
          const Eigen::SelfAdjointEigenSolver<Matrix6d> eig(r.edge_information);
          EXPECT_EQ((eig.eigenvalues().array() > 1e-9 * scale).count(), 6 - free) << what;
          continue;
        }
        if (!r.pose.success) {
          if (r.pose.reason.rfind("degenerate scene", 0) == 0) {
            EXPECT_TRUE(r.pose.degenerate) << what;
          }
          continue;
        }
        ++full;
        EXPECT_LE(translationError(p, r), 0.05) << what;
        EXPECT_LE(rotationErrorDeg(p, r), 2.0) << what;
      }
    if (scene == "floor_6") {
      EXPECT_EQ(full, pairs);
    }
    if (scene == "floor_0") {
      EXPECT_EQ(full, 0);
      EXPECT_EQ(partial, pairs);
    }
    std::printf("%s: %d pairs, %d full poses, %d partial\n", scene.c_str(), pairs, full, partial);
  }
}

TEST(BadInput, EmptyAndInvalidDepthGiveNoEstimate) {
  const auto K = sim::SimulationOptions{}.intrinsics;
  const Pair good = makePair("room", 0, 1);
  const DepthView empty = makeDepthView(cv::Mat::zeros(480, 640, CV_32FC1), K);
  const DepthView nan = makeDepthView(cv::Mat(480, 640, CV_32FC1, cv::Scalar(std::numeric_limits<float>::quiet_NaN())), K);
  for (const DepthView* bad : {&empty, &nan}) {
    const PairResult r1 = registerViews(*bad, good.b);
    EXPECT_FALSE(r1.pose.success);
    EXPECT_FALSE(r1.pose.reason.empty());
    EXPECT_TRUE(r1.edge_information.isZero());  // no pose, no edge
    const PairResult r2 = registerViews(good.a, *bad);
    EXPECT_FALSE(r2.pose.success);
    EXPECT_FALSE(r2.pose.reason.empty());
  }
}

TEST(BadInput, ViewsOfDifferentScenesGiveNoEstimate) {
  const auto K = sim::SimulationOptions{}.intrinsics;
  const DepthView a = makeDepthView(simulation("room").frame(30).depth, K);
  const DepthView b = makeDepthView(simulation("repeated").frame(50).depth, K);
  const PairResult r = registerViews(a, b);
  EXPECT_FALSE(r.pose.success) << "claimed a pose between unrelated views";
  EXPECT_FALSE(r.pose.reason.empty());
}

TEST(GuidedVerification, TooLittleSupportGivesNoEstimate) {
  const Pair p = makePair("room", 3, 9);
  PairParams params;
  params.hypothesise.guided.min_support = 100000;
  const PairResult r = registerViews(p.a, p.b, params);
  EXPECT_FALSE(r.pose.success);
  EXPECT_NE(r.pose.reason.find("guided verification"), std::string::npos) << r.pose.reason;
  EXPECT_GT(r.guided_support, 20);
  params.hypothesise.guided.enabled = false;
  EXPECT_TRUE(registerViews(p.a, p.b, params).pose.success);
}

TEST(BadInput, InvalidParametersThrow) {
  const Pair p = makePair("room", 0, 1);
  PairParams params;
  params.refine.dense.rounds = -1;
  EXPECT_THROW(registerViews(p.a, p.b, params), Error);
  params = PairParams{};
  params.refine.dense.gates_m = {0.05, -1.0};
  EXPECT_THROW(registerViews(p.a, p.b, params), Error);
  params = PairParams{};
  params.certify.visibility.max_violation_ratio = 2.0;
  EXPECT_THROW(registerViews(p.a, p.b, params), Error);
  params = PairParams{};
  params.hypothesise.guided.min_support = 2;
  EXPECT_THROW(registerViews(p.a, p.b, params), Error);
  params = PairParams{};
  params.certify.fallback_max_violation_ratio = -0.1;
  EXPECT_THROW(registerViews(p.a, p.b, params), Error);
  params = PairParams{};
  params.hypothesise.guided.gates.max_distance_m = 0.0;
  EXPECT_THROW(registerViews(p.a, p.b, params), Error);
  params = PairParams{};
  params.hypothesise.guided.gates.lambda = 1.5;
  EXPECT_THROW(registerViews(p.a, p.b, params), Error);
  params = PairParams{};
  params.refine.edges.wide_gate_factor = 0.5;  // "wider" gates narrower than the pixel gates
  EXPECT_THROW(registerViews(p.a, p.b, params), Error);
  params = PairParams{};
  params.refine.edges.wide_min_paired_share = 1.5;
  EXPECT_THROW(registerViews(p.a, p.b, params), Error);
  params = PairParams{};
  params.refine.edges.terms.line_neighbours = 2;
  EXPECT_THROW(registerViews(p.a, p.b, params), Error);
  params = PairParams{};
  params.certify.model_error.sigma_r_deg = -0.5;
  EXPECT_THROW(registerViews(p.a, p.b, params), Error);
  for (double f : {-0.5, 0.001, 1.0, 2.0, std::numeric_limits<double>::quiet_NaN()}) {
    params = PairParams{};
    params.retry.finer_area_factor = f;
    EXPECT_THROW(registerViews(p.a, p.b, params), Error) << f;
  }
}

TEST(GuidedVerification, DensifyRefinesOnTheGuidedAssociations) {
  // guided_densify: RANSAC and the patch refinement run again on the guided associations, which
  // are then what `used` holds; the pose stays within the synthetic tolerance.
  const Pair p = makePair("room", 3, 9);
  PairParams params;
  params.hypothesise.guided.densify = true;
  const PairResult r = registerViews(p.a, p.b, params);
  ASSERT_TRUE(r.pose.success) << r.pose.reason;
  EXPECT_EQ(static_cast<int>(r.used.size()), r.guided_support);
  EXPECT_GT(r.used.size(), r.association.associations.size());
  EXPECT_EQ(r.correspondences.size(), r.used.size());
  const Isometry3 E = p.T_b_a.inverse() * r.pose.T_target_source;
  EXPECT_LT(translationNorm(E), 0.02);
  EXPECT_LT(rotationAngle(E) * 180.0 / M_PI, 1.0);
}

TEST(Determinism, SameInputSamePose) {
  const Pair p = makePair("room", 44, 59);
  const PairResult r1 = registerViews(p.a, p.b), r2 = registerViews(p.a, p.b);
  ASSERT_EQ(r1.pose.success, r2.pose.success);
  EXPECT_TRUE(r1.pose.T_target_source.matrix() == r2.pose.T_target_source.matrix());
  EXPECT_EQ(r1.pose.inliers, r2.pose.inliers);
}

}  // namespace

TEST(FinerScaleRetry, RunsOnlyWhenTheDefaultScaleGivesNoEstimate) {
  const Pair found = makePair("room", 3, 9);
  const PairResult r = registerViews(found.a, found.b);
  ASSERT_TRUE(r.pose.success) << r.pose.reason;
  EXPECT_FALSE(r.retried);
  EXPECT_FALSE(r.finer_scale);
  EXPECT_EQ(r.retry_views, nullptr);
  EXPECT_EQ(r.timings.retry_segmentation_ms, 0.0);
  const auto [va, vb] = viewsOf(r, found.a, found.b);
  EXPECT_EQ(va, &found.a);
  EXPECT_EQ(vb, &found.b);

  // Unrelated views: retried, nothing found either; the result and its indices stay the default
  // scale's, and the reason names both attempts.
  const auto K = sim::SimulationOptions{}.intrinsics;
  const DepthView a = makeDepthView(simulation("room").frame(30).depth, K);
  const DepthView b = makeDepthView(simulation("repeated").frame(50).depth, K);
  const PairResult u = registerViews(a, b);
  EXPECT_FALSE(u.pose.success);
  EXPECT_TRUE(u.retried);
  EXPECT_FALSE(u.finer_scale);
  EXPECT_EQ(u.retry_views, nullptr);
  EXPECT_GT(u.timings.retry_segmentation_ms, 0.0);
  EXPECT_NE(u.pose.reason.find("x the patch area: "), std::string::npos) << u.pose.reason;
  for (const auto& s : u.association.associations) {
    EXPECT_LT(static_cast<std::size_t>(s.a), a.segmentation.patches.size());
    EXPECT_LT(static_cast<std::size_t>(s.b), b.segmentation.patches.size());
  }

  // A degenerate scene is not retried (no scale makes a plane observable), nor is anything with
  // the retry off: with partial poses the plane gives one, without them the view check refuses it.
  const Pair plane = makePair("plane", 0, 2);
  const PairResult on_plane = registerViews(plane.a, plane.b);
  EXPECT_FALSE(on_plane.retried);
  EXPECT_TRUE(on_plane.pose.partial) << on_plane.pose.reason;
  EXPECT_GT(on_plane.views_free_directions, 0);
  PairParams full_only;
  full_only.certify.partial_poses = false;
  const PairResult refused = registerViews(plane.a, plane.b, full_only);
  EXPECT_FALSE(refused.retried);
  EXPECT_TRUE(refused.pose.degenerate);
  EXPECT_FALSE(refused.dense_unobservable);  // the view check, not the dense rounds
  PairParams off;
  off.retry.finer_area_factor = 0.0;
  EXPECT_FALSE(registerViews(a, b, off).retried);
}

TEST(FinerScaleRetry, FindsThePoseWhenThePatchesAreTooLargeForTheOverlap) {
  // Views segmented with 2000 cm^2 patches (about a hundred per view): too few for a consensus. The
  // retry segments each depth image again with the view's own parameters at retry_area_factor x
  // its area (600 cm^2) and registers with mutual associations only; the result's indices refer
  // to those views, and the result is exactly that of registering them without retry or fallback.
  const auto& s = simulation("room");
  const auto K = sim::SimulationOptions{}.intrinsics;
  SuperpixelParams coarse;
  coarse.target_patch_area_m2 = 0.2;
  const auto fa = s.frame(3), fb = s.frame(9);
  const DepthView a = makeDepthView(fa.depth, K, coarse), b = makeDepthView(fb.depth, K, coarse);
  const Isometry3 T_b_a = relativePose(fb.T_world_camera, fa.T_world_camera);
  PairParams off;
  off.retry.finer_area_factor = 0.0;
  const PairResult none = registerViews(a, b, off);
  ASSERT_FALSE(none.pose.success) << "the coarse views alone found the pose: the test needs coarser patches";

  const PairParams defaults;
  const PairResult r = registerViews(a, b, defaults);
  ASSERT_TRUE(r.pose.success) << r.pose.reason;
  EXPECT_TRUE(r.retried);
  EXPECT_TRUE(r.finer_scale);
  ASSERT_NE(r.retry_views, nullptr);
  EXPECT_FALSE(r.used_one_way);
  const auto [va, vb] = viewsOf(r, a, b);
  EXPECT_EQ(va, &r.retry_views->first);
  EXPECT_EQ(vb, &r.retry_views->second);
  EXPECT_DOUBLE_EQ(va->superpixels.target_patch_area_m2, 0.2 * defaults.retry.finer_area_factor);
  EXPECT_GT(va->segmentation.patches.size(), 2 * a.segmentation.patches.size());
  EXPECT_GT(r.timings.retry_segmentation_ms, 0.0);
  const Isometry3 E = T_b_a.inverse() * r.pose.T_target_source;
  EXPECT_LT(translationNorm(E), 0.02);
  EXPECT_LT(rotationAngle(E) * 180.0 / M_PI, 1.0);

  // The same as registering the finer views directly, mutual associations only.
  SuperpixelParams finer = coarse;
  finer.target_patch_area_m2 *= defaults.retry.finer_area_factor;
  const DepthView fa2 = makeDepthView(fa.depth, K, finer), fb2 = makeDepthView(fb.depth, K, finer);
  PairParams mutual_only = off;
  mutual_only.retry.one_way_fallback = false;
  const PairResult direct = registerViews(fa2, fb2, mutual_only);
  ASSERT_TRUE(direct.pose.success);
  EXPECT_TRUE(direct.pose.T_target_source.matrix() == r.pose.T_target_source.matrix());
  EXPECT_EQ(direct.pose.inliers, r.pose.inliers);
  EXPECT_EQ(direct.verified.size(), r.verified.size());

  // The verified associations index the retry's views (some indices lie beyond the coarse views'
  // patches) and are right there.
  ASSERT_FALSE(r.verified.empty());
  int max_a = -1;
  for (const auto& v : r.verified) {
    ASSERT_LT(static_cast<std::size_t>(v.a), va->segmentation.patches.size());
    ASSERT_LT(static_cast<std::size_t>(v.b), vb->segmentation.patches.size());
    max_a = std::max(max_a, v.a);
  }
  EXPECT_GE(static_cast<std::size_t>(max_a), a.segmentation.patches.size());
  const AssociationQuality q =
      evaluateAssociations(r.verified, va->segmentation, vb->segmentation, vb->depth_m, vb->projection.pinhole(), T_b_a);
  EXPECT_GE(q.precision(), 0.9);
}

TEST(ViewSets, TheBestRegistrationIsTheOwnScalePoseAndTheRetryRunsOnlyWithoutOne) {
  // Sources {room 3}, targets {room 9, plane 0}: the room pair registers at the views' own scale,
  // as registerViews() does; the plane pair is a degenerate view. No finer-scale retry runs.
  const Pair room = makePair("room", 3, 9);
  const Pair plane = makePair("plane", 0, 2);
  const ViewSetResult set = registerViewSets({&room.a}, {&room.b, &plane.a}, PairParams{});
  ASSERT_EQ(set.registrations.size(), 2u);
  ASSERT_EQ(set.best, 0);
  const ViewSetRegistration& best = set.registrations[0];
  EXPECT_EQ(best.source, 0u);
  EXPECT_EQ(best.target, 0u);
  EXPECT_FALSE(best.finer_scale);
  const PairResult direct = registerViews(room.a, room.b);
  ASSERT_TRUE(best.result.pose.success) << best.result.pose.reason;
  EXPECT_TRUE(direct.pose.T_target_source.matrix() == best.result.pose.T_target_source.matrix());
  EXPECT_FALSE(set.registrations[1].result.pose.success);
  EXPECT_TRUE(set.registrations[1].result.pose.degenerate);

  // Views segmented with 2000 cm^2 patches: no pair registers at their own scale, so the pairs the
  // retry applies to run again at the finer scale; the room pair's estimate is then the best, the
  // same pose registerViews() gives with its own retry.
  const auto& s = simulation("room");
  const auto K = sim::SimulationOptions{}.intrinsics;
  SuperpixelParams coarse;
  coarse.target_patch_area_m2 = 0.2;
  const DepthView a = makeDepthView(s.frame(3).depth, K, coarse), b = makeDepthView(s.frame(9).depth, K, coarse);
  const ViewSetResult fine = registerViewSets({&a}, {&b, &plane.a}, PairParams{});
  ASSERT_GE(fine.best, 0);
  const ViewSetRegistration& f = fine.registrations[static_cast<std::size_t>(fine.best)];
  ASSERT_TRUE(f.result.pose.success) << f.result.pose.reason;
  EXPECT_TRUE(f.finer_scale);
  EXPECT_EQ(f.target, 0u);
  EXPECT_EQ(fine.registrations.size(), 3u);  // two at the own scale, the room pair once more (the plane's view is degenerate)
  const PairResult retried = registerViews(a, b);
  ASSERT_TRUE(retried.retried && retried.pose.success);
  EXPECT_TRUE(retried.pose.T_target_source.matrix() == f.result.pose.T_target_source.matrix());
  EXPECT_TRUE(fine.notes.empty());
}

TEST(FinerScaleRetry, ClaimsNoLookAlikePoseOnRepeatedObjects) {
  // Repeated boxes 33 -> 43 and 3 -> 13: the default scale gives no estimate; at 0.3 x the area the
  // mutual associations align look-alike boxes (90 deg and 8 deg off, 12-18 % violations), which
  // the retry's visibility limit (one_way_max_violation_ratio, 8 %) declines. Loosened to 30 %
  // (the default scale's limit was 30 % until it became 15 %, which declines them too), the wrong
  // pose is claimed: those limits are what decline it, and the uniqueness test. (Since the extrapolated dense rounds,
  // docs/pipeline.md, 3 -> 13 is registered right at the default scale, 1.4 mm off: see below.)
  for (const auto& [from, to] : {std::pair{33, 43}, std::pair{3, 13}}) {
    const Pair p = makePair("repeated", from, to);
    const PairResult r = registerViews(p.a, p.b);
    if (r.pose.success) {
      const Isometry3 E = p.T_b_a.inverse() * r.pose.T_target_source;
      EXPECT_LT(translationNorm(E), 0.02) << from << " -> " << to;
      EXPECT_LT(rotationAngle(E) * 180.0 / M_PI, 1.0) << from << " -> " << to;
    } else {
      EXPECT_TRUE(r.retried) << r.pose.reason;
      EXPECT_NE(r.pose.reason.find("x the patch area: visibility check"), std::string::npos) << r.pose.reason;
    }
    PairParams loose;
    loose.certify.fallback_max_violation_ratio = 0.3;
    loose.certify.visibility.max_violation_ratio = 0.3;
    loose.certify.visibility.max_two_way_violation_ratio = 1.0;  // which declines a look-alike too
    loose.refine.slide_scan.enabled = false;  // 3 -> 13's loosened pose slid along a box: the scan moves it right
    loose.certify.min_likelihood_ratio = 0.0;  // the uniqueness test declines 33 -> 43's look-alike too (below)
    if (from == 3) {
      // The 16 rounds with the extrapolation: the default scale's pose, right; nothing to retry.
      const PairResult right = registerViews(p.a, p.b, loose);
      ASSERT_TRUE(right.pose.success) << right.pose.reason;
      EXPECT_EQ(right.retry_views, nullptr);
      EXPECT_LT(translationNorm(p.T_b_a.inverse() * right.pose.T_target_source), 0.02);
      // The former rounds (8, plain) leave the default scale without a pose; the retry's
      // look-alike is claimed under the loosened limits.
      loose.refine.dense.max_rounds = 8;
      loose.refine.dense.extrapolation_max = 0.0;
    }
    const PairResult w = registerViews(p.a, p.b, loose);
    ASSERT_TRUE(w.pose.success) << from << " -> " << to << ": " << w.pose.reason;
    EXPECT_NE(w.retry_views, nullptr);
    // Wrong: 33 -> 43 90 deg off, 3 -> 13 9 cm off (the converged dense rounds; 3 rounds: 29 cm).
    EXPECT_GT(translationNorm(p.T_b_a.inverse() * w.pose.T_target_source), 0.05) << from << " -> " << to;
    // The two-way limit alone declines the 90-deg look-alike (33 -> 43), whose violations both
    // views see; not 3 -> 13's 9 cm slide along a box, which the one-direction limits decline.
    if (from == 33) {
      PairParams two_way = loose;
      two_way.certify.visibility.max_two_way_violation_ratio = PairParams{}.certify.visibility.max_two_way_violation_ratio;
      const PairResult d = registerViews(p.a, p.b, two_way);
      EXPECT_FALSE(d.pose.success);
      EXPECT_NE(d.pose.reason.find("seen from both views"), std::string::npos) << d.pose.reason;
      // So does the certificate's uniqueness test: RANSAC's distinct alternative explains the
      // views almost as well as the look-alike.
      PairParams unique = loose;
      unique.certify.min_likelihood_ratio = PairParams{}.certify.min_likelihood_ratio;
      const PairResult u = registerViews(p.a, p.b, unique);
      EXPECT_FALSE(u.pose.success);
      EXPECT_NE(u.pose.reason.find("not unique"), std::string::npos) << u.pose.reason;
    }
    loose.refine.slide_scan.enabled = true;
    const PairResult s = registerViews(p.a, p.b, loose);
    std::printf("%d -> %d loosened, with the slide scan: %s, %s, %.3f m / %.2f deg off\n", from, to,
                s.pose.success ? "claimed" : "declined", s.slide.summary().c_str(),
                translationNorm(p.T_b_a.inverse() * s.pose.T_target_source),
                rotationAngle(p.T_b_a.inverse() * s.pose.T_target_source) * 180.0 / M_PI);
  }
}

TEST(DenseSupport, ALookAlikePoseThatExplainsLittleSurfaceIsDeclined) {
  // The room with noise seed 3, 39 -> 54 (15 frames across the roll): the mutual associations
  // give no pose; with the one-way partners RANSAC aligns a look-alike (8 inliers) 2.3 m / 90 deg
  // off with 5 % violations, under the fallback's 8 % limit. Its last dense round has 100 terms;
  // right poses of the benchmarks have at least 556 (min_dense_terms 300, docs/pipeline.md).
  const auto [a, b, T_b_a] = makePair("room", 39, 54, 3);
  PairParams params;
  params.retry.finer_area_factor = 0.0;
  const PairResult r = registerViews(a, b, params);
  if (r.pose.success) {  // right, or declined
    EXPECT_LT(translationNorm(T_b_a.inverse() * r.pose.T_target_source), 0.02);
  } else {
    EXPECT_NE(r.pose.reason.find("min_dense_terms"), std::string::npos) << r.pose.reason;
  }
  // With the retry too (its poses meet the same rule).
  const PairResult retried = registerViews(a, b);
  if (retried.pose.success) {
    EXPECT_LT(translationNorm(T_b_a.inverse() * retried.pose.T_target_source), 0.02);
  }
  // Without the limit the wrong pose is claimed: the limit is what declines it.
  params.certify.min_dense_terms = 0;
  const PairResult w = registerViews(a, b, params);
  ASSERT_TRUE(w.pose.success) << w.pose.reason;
  EXPECT_TRUE(w.used_one_way);
  EXPECT_GT(translationNorm(T_b_a.inverse() * w.pose.T_target_source), 1.0);
  EXPECT_LT(w.dense_terms, 300);
  params.certify.min_dense_terms = -1;
  EXPECT_THROW(registerViews(a, b, params), Error);
}
