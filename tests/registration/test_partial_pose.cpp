// Partial poses (partial_pose.h): a dense problem over one plane leaves its two in-plane
// translations and the rotation about its normal free; the solve keeps the start pose there
// (solution remapping), the information is zero exactly along the free directions, the error is
// judged in the observed directions only, and a prediction fills the free ones.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <random>

#include "gasp/core/pose_perturbation.h"
#include "gasp/registration/partial_pose.h"
#include "gasp/registration/refinement.h"
#include "synthetic_scene.h"

using namespace gasp;
using namespace gasp::test;

namespace {

/// Dense terms of the floor plane y = 1 (normal (0, -1, 0)) seen by the source, mapped by T.
std::vector<PointToPlane> floorTerms(const Isometry3& T, unsigned seed = 5) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> s(-1.0, 1.0);
  const Plane p = plane({0.0, 1.0, 2.5}, {0, -1, 0}, 1.5, 1.5);
  std::vector<PointToPlane> dense;
  for (int i = 0; i < 400; ++i) {
    const Eigen::Vector3d a = p.centre + s(rng) * p.half_u * p.u + s(rng) * p.half_v * p.v;
    const Eigen::Vector3d b = p.centre + s(rng) * p.half_u * p.u + s(rng) * p.half_v * p.v;
    dense.push_back({a, T * b, T.linear() * p.normal, 1.0});
  }
  return dense;
}

Isometry3 motion(const Eigen::Vector3d& t, double angle_rad, const Eigen::Vector3d& axis) {
  Isometry3 T = Isometry3::Identity();
  T.linear() = Eigen::AngleAxisd(angle_rad, axis.normalized()).toRotationMatrix();
  T.translation() = t;
  return T;
}

RefinementParams partialSolver() {
  RefinementParams p;
  p.degeneracy = DegeneracyParams{1e-3, 0.05};
  p.partial_poses = true;
  return p;
}

}  // namespace

TEST(PartialPose, OnePlaneGivesAPartialPoseRightInItsObservedDirections) {
  const Isometry3 T = motion({0.05, -0.03, 0.1}, 0.1, {1, 0.5, 0.2});
  // Start off in every direction: 8 cm along the floor, 3 cm above it, tilted 2 deg, turned 5 deg.
  const Isometry3 start = motion({0.08, 0.03, 0.0}, 0.0, {0, 1, 0}) * expLeft((Vector6() << 0, 0, 0, 0.035, 0.09, 0).finished()) * T;
  const RegistrationResult r = refinePose({}, start, partialSolver(), floorTerms(T));
  ASSERT_TRUE(r.partial) << r.reason;
  EXPECT_FALSE(r.success);
  EXPECT_TRUE(r.degenerate);
  EXPECT_TRUE(r.estimated());
  EXPECT_EQ(r.unobservable_directions.cols(), 3);
  const ObservedError e = observedError(r, T);
  EXPECT_LT(e.translation_m, 1e-4);
  EXPECT_LT(e.rotation_deg, 1e-3);
  // The free directions stay where the start had them: the in-plane offset is still there.
  EXPECT_GT(translationError(r.T_target_source, T), 0.05);
  // Without partial poses the same problem is no estimate.
  RefinementParams full_only = partialSolver();
  full_only.partial_poses = false;
  const RegistrationResult refused = refinePose({}, start, full_only, floorTerms(T));
  EXPECT_FALSE(refused.estimated());
  EXPECT_TRUE(refused.degenerate);
}

TEST(PartialPose, InformationIsZeroExactlyAlongTheFreeDirections) {
  const Isometry3 T = motion({0.05, -0.03, 0.1}, 0.1, {1, 0.5, 0.2});
  const RegistrationResult r = refinePose({}, T, partialSolver(), floorTerms(T));
  ASSERT_TRUE(r.partial) << r.reason;
  const Matrix6d I = observedInformation(r, r.information);
  const auto twists = unobservableTwists(r);
  const double scale = r.information.norm();
  for (Eigen::Index k = 0; k < twists.cols(); ++k) EXPECT_LT((I * twists.col(k)).norm(), 1e-9 * scale);
  // The plane's normal translation and its two tilts keep their information.
  const Eigen::SelfAdjointEigenSolver<Matrix6d> eig(I);
  EXPECT_EQ((eig.eigenvalues().array() > 1e-9 * scale).count(), 3);
  // With a covariance added in the observed directions only, still zero along the free ones.
  Matrix6d C = Matrix6d::Zero();
  C.diagonal() << 1e-4, 1e-4, 1e-4, 1.7e-4, 1.7e-4, 1.7e-4;
  const Matrix6d Ic = observedInformationWithCovariance(r, r.information, C);
  for (Eigen::Index k = 0; k < twists.cols(); ++k) EXPECT_LT((Ic * twists.col(k)).norm(), 1e-9 * Ic.norm());
  // Its observed part is less certain than the information alone (the covariance adds).
  EXPECT_LT(Ic.trace(), I.trace());
}

TEST(PartialPose, APredictionFillsTheFreeDirectionsAndLeavesTheObservedOnes) {
  const Isometry3 T = motion({0.05, -0.03, 0.1}, 0.1, {1, 0.5, 0.2});
  const Isometry3 start = motion({0.2, 0.0, -0.15}, 0.0, {0, 1, 0}) * T;  // slid 25 cm along the floor
  const RegistrationResult r = refinePose({}, start, partialSolver(), floorTerms(T));
  ASSERT_TRUE(r.partial) << r.reason;
  // The prediction: the truth lifted 4 cm off the floor -- right in the free directions, wrong in
  // the observed ones.
  const Eigen::Vector3d lift = 0.04 * (T.linear() * Eigen::Vector3d(0, -1, 0));  // along the floor's normal
  const Isometry3 predicted = motion(lift, 0.0, {0, 1, 0}) * T;
  const Isometry3 fused = withPrediction(r, predicted);
  RegistrationResult at_fused = r;
  at_fused.T_target_source = fused;
  const ObservedError e = observedError(at_fused, T);
  EXPECT_LT(e.translation_m, 1e-3);  // the observed directions are still the registration's
  EXPECT_LT(e.rotation_deg, 0.01);
  EXPECT_LT(translationError(fused, T), 1e-3);  // the slide is the prediction's (right) one
  EXPECT_LT(rotationErrorDeg(fused, T), 0.01);
  // Without free directions the prediction changes nothing.
  RegistrationResult full = r;
  full.unobservable_directions.resize(6, 0);
  EXPECT_TRUE(withPrediction(full, predicted).isApprox(r.T_target_source));
}

TEST(PartialPose, AFreeDirectionFoundTwiceCountsOnce) {
  const Isometry3 T = motion({0.05, -0.03, 0.1}, 0.1, {1, 0.5, 0.2});
  const RegistrationResult r = refinePose({}, T, partialSolver(), floorTerms(T));
  ASSERT_TRUE(r.partial) << r.reason;
  // The same three directions again, a few degrees off (another analysis of the same views).
  Eigen::Matrix<double, 6, Eigen::Dynamic> again = unobservableTwists(r);
  again(1, 0) += 0.05, again(4, 2) += 0.02;
  EXPECT_EQ(unitedDirections(r, again).cols(), 3);
  // A direction at right angles to them (the floor's normal) is new.
  Eigen::Matrix<double, 6, Eigen::Dynamic> normal(6, 1);
  normal << 0, 1, 0, 0, 0, 0;
  EXPECT_EQ(unitedDirections(r, normal).cols(), 4);
}
