// Point-to-line terms along occluding edges (edge_terms.h) on a hand-made scene that point-to-plane
// terms cannot register: a camera looking down at a floor 2 m away with a slab (a table top)
// 0.4 m above it. Both surfaces are parallel planes, so a slide along them costs point-to-plane
// terms nothing; the slab's border does.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <vector>

#include "gasp/core/error.h"
#include "gasp/pipeline/certify_stage.h"
#include "gasp/pipeline/edge_terms.h"
#include "gasp/pipeline/projective_terms.h"
#include "gasp/pipeline/refine_stage.h"
#include "gasp/registration/refinement.h"
#include "gasp/superpixels/depth_superpixels.h"

using namespace gasp;

namespace {

/// The floor (z = 2 m in the world frame, camera looking along +z) and a slab at z = 1.6 m over
/// x in [-0.3, 0.2], y in [-0.25, 0.3], seen by a camera at `offset` (world = camera + offset).
DepthView slabView(const Eigen::Vector3d& offset) {
  DepthView v;
  v.projection = CameraIntrinsics::rosDefault();
  v.depth_m = cv::Mat(480, 640, CV_32FC1);
  for (int r = 0; r < 480; ++r)
    for (int c = 0; c < 640; ++c) {
      const Eigen::Vector3d ray = v.projection.ray(c, r);
      // Slab plane at world z 1.6: camera z = 1.6 - offset.z.
      const double zs = 1.6 - offset.z();
      const Eigen::Vector3d ps = ray * zs + offset;
      const bool on_slab = ps.x() >= -0.3 && ps.x() <= 0.2 && ps.y() >= -0.25 && ps.y() <= 0.3;
      v.depth_m.at<float>(r, c) = static_cast<float>(on_slab ? zs : 2.0 - offset.z());
    }
  v.segmentation = segmentDepthSuperpixels(v.depth_m, v.projection);
  return v;
}

}  // namespace

TEST(EdgeTerms, EdgePixelsAreTheForegroundSideOfDepthJumps) {
  const DepthView v = slabView(Eigen::Vector3d::Zero());
  EdgeTermParams p;
  p.pixel_step = 1;
  const EdgePoints e = findEdgePoints(v, p);
  ASSERT_GT(e.points.size(), 500u);  // the slab's outline, about 2 x (160 + 180) px
  for (std::size_t i = 0; i < e.points.size(); ++i) EXPECT_NEAR(e.points[i].z(), 1.6, 1e-5) << "not the slab";
  // A view without jumps has none.
  DepthView flat = v;
  flat.depth_m.setTo(2.0f);
  EXPECT_TRUE(findEdgePoints(flat, p).points.empty());
  p.pixel_step = 0;
  EXPECT_THROW(findEdgePoints(v, p), Error);
}

TEST(EdgeTerms, PinTheSlideThatPlaneTermsLeaveFree) {
  // Source and target cameras 6 cm apart along x; the refinement starts at the identity (6 cm
  // off, along the planes).
  const DepthView target = slabView(Eigen::Vector3d::Zero());
  const DepthView source = slabView(Eigen::Vector3d(0.06, 0.0, 0.0));
  Isometry3 T_true = Isometry3::Identity();
  T_true.translation() = Eigen::Vector3d(0.06, 0.0, 0.0);  // p_target = p_source + offset
  const Isometry3 T0 = Isometry3::Identity();

  const EdgeTermParams ep{};
  const EdgeTargets edges(target, ep);
  ASSERT_GT(edges.size(), 50u);
  const EdgePoints source_edges = findEdgePoints(source, ep);
  // At the true pose the edge residuals vanish (up to the pixel grid); at the identity they do not.
  double at_true = 0.0, at_start = 0.0;
  const auto true_terms = edges.terms(source_edges, T_true, 0.1);
  const auto start_terms = edges.terms(source_edges, T0, 0.1);
  ASSERT_FALSE(true_terms.empty());
  ASSERT_FALSE(start_terms.empty());
  for (const auto& t : true_terms) at_true += std::abs(t.n_target.dot(T_true * t.p_source - t.q_target));
  for (const auto& t : start_terms) at_start += std::abs(t.n_target.dot(T0 * t.p_source - t.q_target));
  EXPECT_LT(at_true / true_terms.size(), 0.006);
  EXPECT_GT(at_start / start_terms.size(), 0.015);

  // Refinement from the identity, three rounds with shrinking gates, as the pair pipeline does.
  RefinementParams rp;
  rp.degeneracy.min_eigenvalue_ratio = 1e-3;
  auto refine = [&](bool with_edges) {
    Isometry3 T = T0;
    RegistrationResult r;
    for (double gate : {0.10, 0.05, 0.03}) {
      ProjectiveTermParams pp;
      pp.max_distance_m = gate;
      auto terms = projectiveTerms(source, target, T, pp);
      if (with_edges) {
        const auto more = edges.terms(source_edges, T, gate);
        terms.insert(terms.end(), more.begin(), more.end());
      }
      r = refinePose({}, T, rp, terms);
      if (!r.success) return r;
      T = r.T_target_source;
    }
    return r;
  };
  const RegistrationResult planes_only = refine(false);
  std::printf("planes only: %s, %.4f m off\n", planes_only.success ? "pose" : planes_only.reason.c_str(),
              (planes_only.T_target_source.translation() - T_true.translation()).norm());
  // Planes alone: the slide is unobservable (flagged) or not corrected.
  if (planes_only.success) {
    EXPECT_GT((planes_only.T_target_source.translation() - T_true.translation()).norm(), 0.03);
  } else {
    EXPECT_TRUE(planes_only.degenerate) << planes_only.reason;
  }
  const RegistrationResult with_edges = refine(true);
  ASSERT_TRUE(with_edges.success) << with_edges.reason;
  std::printf("with edges: %.4f m off\n", (with_edges.T_target_source.translation() - T_true.translation()).norm());
  EXPECT_LT((with_edges.T_target_source.translation() - T_true.translation()).norm(), 0.01);
}

namespace {

/// A diamond (a square turned 45 deg in the image, half-diagonal `r` px, centred at (cu, cv)) at
/// 1.6 m in front of a plane at 2 m: its outline runs along both image diagonals.
DepthView diamondView(double cu, double cv, double r) {
  DepthView v;
  v.projection = CameraIntrinsics::rosDefault();
  v.depth_m = cv::Mat(480, 640, CV_32FC1);
  for (int row = 0; row < 480; ++row)
    for (int c = 0; c < 640; ++c)
      v.depth_m.at<float>(row, c) = std::abs(c - cu) + std::abs(row - cv) <= r ? 1.6f : 2.0f;
  return v;
}

}  // namespace

TEST(EdgeTerms, SamplingDoesNotDependOnTheEdgeDirection) {
  // The diamond's outline (4 sides of r * sqrt(2) px) against an axis-aligned square of the same
  // perimeter: about as many edge points per pixel of outline, at every sub-block offset (a rule
  // on (u + v) alone kept all or none of an anti-diagonal side).
  const EdgeTermParams p{};
  const double r = 100.0;
  const double perimeter = 4.0 * r * std::sqrt(2.0);
  DepthView square;
  square.projection = CameraIntrinsics::rosDefault();
  square.depth_m = cv::Mat(480, 640, CV_32FC1, cv::Scalar(2.0f));
  const int side = static_cast<int>(std::lround(perimeter / 4.0));
  square.depth_m(cv::Rect(200, 100, side, side)).setTo(1.6f);
  const double per_px_square = static_cast<double>(findEdgePoints(square, p).points.size()) / perimeter;
  ASSERT_GT(per_px_square, 0.05);
  for (int shift = 0; shift < p.pixel_step; ++shift) {
    const double n = static_cast<double>(findEdgePoints(diamondView(320 + shift, 240, r), p).points.size());
    EXPECT_GT(n / perimeter, 0.6 * per_px_square) << "shift " << shift;
    EXPECT_LT(n / perimeter, 2.0 * per_px_square) << "shift " << shift;
  }
}

TEST(EdgeTerms, BadInputGivesNoTermsOrAClearError) {
  EdgeTermParams p;
  // All-invalid depth: no edge points, no targets, no terms.
  DepthView empty;
  empty.projection = CameraIntrinsics::rosDefault();
  empty.depth_m = cv::Mat(480, 640, CV_32FC1, cv::Scalar(std::numeric_limits<float>::quiet_NaN()));
  EXPECT_TRUE(findEdgePoints(empty, p).points.empty());
  const EdgeTargets none(empty, p);
  EXPECT_EQ(none.size(), 0u);
  const DepthView slab = slabView(Eigen::Vector3d::Zero());
  EXPECT_TRUE(none.terms(findEdgePoints(slab, p), Isometry3::Identity(), 0.1).empty());
  // Fewer target edge points than line_neighbours: no direction, no targets.
  DepthView speck = empty;
  speck.depth_m.setTo(2.0f);
  speck.depth_m.at<float>(240, 320) = 1.0f;
  EXPECT_EQ(EdgeTargets(speck, p).size(), 0u);
  // A non-finite pose gives no terms.
  const EdgeTargets targets(slab, p);
  Isometry3 bad = Isometry3::Identity();
  bad.translation().x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(targets.terms(findEdgePoints(slab, p), bad, 0.1).empty());
  // Depth of the wrong type: a clear error, not a read past the rows.
  DepthView raw = slab;
  raw.depth_m = cv::Mat(480, 640, CV_16UC1, cv::Scalar(8000));
  EXPECT_THROW(findEdgePoints(raw, p), Error);
  EXPECT_THROW(EdgeTargets(raw, p), Error);
  // Invalid parameters name themselves.
  for (auto broken : std::vector<std::function<void(EdgeTermParams&)>>{
           [](EdgeTermParams& q) { q.line_neighbours = 2; },
           [](EdgeTermParams& q) { q.min_jump_m = std::numeric_limits<double>::quiet_NaN(); },
           [](EdgeTermParams& q) { q.jump_per_m2 = -1.0; },
           [](EdgeTermParams& q) { q.weight = -1.0; },
           [](EdgeTermParams& q) { q.max_distance_m = 0.0; }}) {
    EdgeTermParams q;
    broken(q);
    EXPECT_THROW(validate(q), Error);
  }
}

TEST(EdgeTerms, WideEdgeGatesRescueASlideBeyondThePixelGates) {
  // The slab scene slid 12 cm along its planes: beyond the last pixel gate (0.10 m in the first
  // round), so no edge pairs and the planes alone leave the slide free -- the first refinement is
  // degenerate, and without partial rounds it ends there. The second refinement with 3x wider
  // edge gates pairs the slab's outline.
  const Eigen::Vector3d slide(0.12, 0.0, 0.0);
  const DepthView target = slabView(Eigen::Vector3d::Zero());
  const DepthView source = slabView(slide);
  RegistrationResult start;
  start.success = true;
  start.T_target_source = Isometry3::Identity();
  RefineParams params;
  const FreeSpaceTest free_space = freeSpaceTest(source, target, CertifyParams{}, false);
  {
    // With partial rounds (the default) the first refinement goes on in the observed directions
    // and its edges pair as the pose settles: it finds the slide by itself.
    const Refinement partial = refine(source, target, start, {}, params, free_space);
    ASSERT_TRUE(partial.pose.success) << partial.pose.reason;
    EXPECT_LT((partial.pose.T_target_source.translation() - slide).norm(), 0.01);
  }
  params.solver.partial_poses = false;
  const Refinement wide = refine(source, target, start, {}, params, free_space);
  ASSERT_TRUE(wide.pose.success) << wide.pose.reason;
  EXPECT_TRUE(wide.wide_edge_pose);
  std::printf("wide edge gates: %.4f m off\n", (wide.pose.T_target_source.translation() - slide).norm());
  EXPECT_LT((wide.pose.T_target_source.translation() - slide).norm(), 0.01);
  params.edges.wide_gate_factor = 0.0;  // without the second refinement: no pose, or a slid one
  const Refinement narrow = refine(source, target, start, {}, params, free_space);
  EXPECT_FALSE(narrow.wide_edge_pose);
  std::printf("without: %s\n", narrow.pose.success ? "a pose" : narrow.pose.reason.c_str());
  if (narrow.pose.success) {
    EXPECT_GT((narrow.pose.T_target_source.translation() - slide).norm(), 0.05);
  }
}
