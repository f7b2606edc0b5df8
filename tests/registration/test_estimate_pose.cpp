// The composition RANSAC + refinement: within 1 cm / 0.5 deg under noise and up to 70 % outliers,
// exact without noise; RANSAC-only vs refined; degenerate scenes and bad input are not claimed.
#include <gtest/gtest.h>

#include <algorithm>
#include <iterator>
#include <limits>

#include "gasp/registration/register_patches.h"
#include "synthetic_scene.h"

namespace {

using namespace gasp;
using namespace gasp::test;

/// 500 patches: at 70 % outliers 150 inliers, enough for 1 cm at the camera, 3-4 m from the scene.
SceneOptions noisy(double outliers, unsigned seed = 7) {
  SceneOptions o;
  o.n = 500;
  o.outlier_fraction = outliers;
  o.centroid_sigma_m = 0.005;
  o.normal_sigma_deg = 2.0;
  o.seed = seed;
  return o;
}

TEST(EstimatePose, NoiseFreeIsExact) {
  for (const Isometry3& T : testMotions()) {
    SceneOptions o;
    o.outlier_fraction = 0.5;
    const Scene s = makeScene(roomCorner(), T, o);
    const RegistrationResult r = estimatePose(s.correspondences);
    ASSERT_TRUE(r.success) << r.reason;
    EXPECT_LT(translationError(r.T_target_source, T), 1e-6);
    EXPECT_LT(rotationErrorDeg(r.T_target_source, T), 1e-5);
    EXPECT_EQ(r.inliers, selectInliers(s.correspondences, T, RansacParams().inlier));
  }
}

TEST(EstimatePose, NoisyWithOutliersIsWithinOneCentimetreAndHalfADegree) {
  for (const Isometry3& T : testMotions()) {
    for (double outliers : {0.3, 0.5, 0.7}) {
      const Scene s = makeScene(roomCorner(), T, noisy(outliers));
      const RegistrationResult r = estimatePose(s.correspondences);
      ASSERT_TRUE(r.success) << r.reason;
      EXPECT_LT(translationError(r.T_target_source, T), 0.01) << "outliers " << outliers;
      EXPECT_LT(rotationErrorDeg(r.T_target_source, T), 0.5) << "outliers " << outliers;
      const auto truth = selectInliers(s.correspondences, T, RansacParams().inlier);
      std::vector<int> diff;
      std::set_symmetric_difference(r.inliers.begin(), r.inliers.end(), truth.begin(), truth.end(),
                                    std::back_inserter(diff));
      EXPECT_LE(diff.size(), truth.size() / 20) << "outliers " << outliers;
      EXPECT_EQ(r.num_inliers, static_cast<int>(r.inliers.size()));
      EXPECT_GT(r.ransac_iterations, 0);
      EXPECT_GE(r.ransac_ms, 0.0);
      EXPECT_GT(r.refine_ms, 0.0);
    }
  }
}

TEST(EstimatePose, RefinementHelpsWhenCentroidsSlideAlongTheSurfaces) {
  // Patches cut differently in the two views: target centroids slide 2.5 cm along the surfaces
  // (one direction), which biases centroid fits (RANSAC) but not point-to-plane residuals. (With
  // exactly corresponding centroids the RANSAC fit, 3 components per pair, is more accurate.)
  double ransac_t = 0.0, refined_t = 0.0, ransac_r = 0.0, refined_r = 0.0;
  for (unsigned seed = 1; seed <= 10; ++seed) {
    const Isometry3 T = testMotions()[seed % 6];
    SceneOptions o = noisy(0.3, seed);
    o.in_plane_bias_m = Eigen::Vector3d(0.025, 0.0, 0.0);
    const Scene s = makeScene(roomCorner(), T, o);
    PoseEstimationParams p;
    p.refine = false;
    const RegistrationResult ransac_only = estimatePose(s.correspondences, p);
    const RegistrationResult refined = estimatePose(s.correspondences);
    ASSERT_TRUE(ransac_only.success && refined.success) << ransac_only.reason << refined.reason;
    EXPECT_EQ(ransac_only.iterations, 0);
    EXPECT_GT(refined.iterations, 0);
    EXPECT_GT(ransac_only.information_eigenvalues(0), 0.0);  // evaluated at the RANSAC pose
    ransac_t += translationError(ransac_only.T_target_source, T);
    refined_t += translationError(refined.T_target_source, T);
    ransac_r += rotationErrorDeg(ransac_only.T_target_source, T);
    refined_r += rotationErrorDeg(refined.T_target_source, T);
  }
  EXPECT_LT(refined_t, 0.5 * ransac_t);
  EXPECT_LT(refined_r, 0.9 * ransac_r);
  EXPECT_LT(refined_t / 10, 0.01);
}

TEST(EstimatePose, DegenerateSceneIsNotClaimedEvenWithoutRefinement) {
  const std::vector<Plane> wall = {plane({0.0, 0.0, 3.0}, {0, 0, -1}, 1.5, 1.0)};
  const Scene s = makeScene(wall, testMotions()[0], noisy(0.2));
  for (bool refine : {true, false}) {
    PoseEstimationParams p;
    p.refine = refine;
    const RegistrationResult r = estimatePose(s.correspondences, p);
    EXPECT_FALSE(r.success);
    EXPECT_TRUE(r.degenerate);
    EXPECT_NE(r.reason.find("unobservable"), std::string::npos) << r.reason;
  }
}

TEST(EstimatePose, BadInputGivesAReasonWithoutThrowing) {
  const Scene good = makeScene(roomCorner(), testMotions()[0], {});
  for (std::size_t n : {0u, 1u, 2u}) {
    const RegistrationResult r = estimatePose({good.correspondences.begin(), good.correspondences.begin() + n});
    EXPECT_FALSE(r.success);
    EXPECT_NE(r.reason.find("too few"), std::string::npos) << r.reason;
  }
  auto nan = good.correspondences;
  nan[0].n_source.z() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(estimatePose(nan).reason.find("non-finite"), std::string::npos);
  SceneOptions o;
  o.outlier_fraction = 1.0;
  const RegistrationResult all_outliers = estimatePose(makeScene(roomCorner(), testMotions()[0], o).correspondences);
  EXPECT_FALSE(all_outliers.success);
  EXPECT_EQ(all_outliers.reason.rfind("RANSAC: ", 0), 0u) << all_outliers.reason;
}

TEST(EstimatePose, SameSeedSameResult) {
  const Scene s = makeScene(roomCorner(), testMotions()[5], noisy(0.6));
  const RegistrationResult a = estimatePose(s.correspondences), b = estimatePose(s.correspondences);
  EXPECT_TRUE(a.T_target_source.matrix() == b.T_target_source.matrix());
  EXPECT_EQ(a.inliers, b.inliers);
  EXPECT_TRUE(a.information == b.information);
  EXPECT_EQ(a.iterations, b.iterations);
}

}  // namespace
