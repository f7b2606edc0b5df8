// Point-to-line terms along occluding edges (edge_terms.h) on a hand-made scene that point-to-plane
// terms cannot register: a camera looking down at a floor 2 m away with a slab (a table top)
// 0.4 m above it. Both surfaces are parallel planes, so a slide along them costs point-to-plane
// terms nothing; the slab's border does.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cstdio>

#include "gasp/core/error.h"
#include "gasp/pipeline/edge_terms.h"
#include "gasp/pipeline/projective_terms.h"
#include "gasp/registration/refinement.h"
#include "gasp/superpixels/depth_superpixels.h"

using namespace gasp;

namespace {

/// The floor (z = 2 m in the world frame, camera looking along +z) and a slab at z = 1.6 m over
/// x in [-0.3, 0.2], y in [-0.25, 0.3], seen by a camera at `offset` (world = camera + offset).
DepthView slabView(const Eigen::Vector3d& offset) {
  DepthView v;
  v.intrinsics = CameraIntrinsics::rosDefault();
  v.depth_m = cv::Mat(480, 640, CV_32FC1);
  for (int r = 0; r < 480; ++r)
    for (int c = 0; c < 640; ++c) {
      const Eigen::Vector3d ray((c - v.intrinsics.cx) / v.intrinsics.fx, (r - v.intrinsics.cy) / v.intrinsics.fy, 1.0);
      // Slab plane at world z 1.6: camera z = 1.6 - offset.z.
      const double zs = 1.6 - offset.z();
      const Eigen::Vector3d ps = ray * zs + offset;
      const bool on_slab = ps.x() >= -0.3 && ps.x() <= 0.2 && ps.y() >= -0.25 && ps.y() <= 0.3;
      v.depth_m.at<float>(r, c) = static_cast<float>(on_slab ? zs : 2.0 - offset.z());
    }
  v.segmentation = segmentDepthSuperpixels(v.depth_m, v.intrinsics);
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
