// Extrapolation of creeping dense rounds (step_extrapolation.h): the power of a step about a
// centre, and the jump that two successive steps of a geometrically converging iteration give.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "gasp/pipeline/step_extrapolation.h"

using namespace gasp;

namespace {

Isometry3 rotationAbout(const Eigen::Vector3d& axis, double angle, const Eigen::Vector3d& centre) {
  Isometry3 T = Isometry3::Identity();
  T.linear() = Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
  T.translation() = centre - T.linear() * centre;
  return T;
}

Isometry3 translation(const Eigen::Vector3d& t) {
  Isometry3 T = Isometry3::Identity();
  T.translation() = t;
  return T;
}

double distance(const Isometry3& A, const Isometry3& B) { return (A.matrix() - B.matrix()).norm(); }

/// A cloud of points around `centre` (a scene's patch centroids).
std::vector<Eigen::Vector3d> cloudAround(const Eigen::Vector3d& centre) {
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 40; ++i)
    points.push_back(centre + Eigen::Vector3d(std::sin(1.3 * i), std::cos(0.7 * i), 0.5 * std::sin(2.1 * i)));
  return points;
}

/// The mean of the points.
Eigen::Vector3d centreOf(const std::vector<Eigen::Vector3d>& points) {
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (const auto& p : points) c += p;
  return c / static_cast<double>(points.size());
}

}  // namespace

TEST(StepPower, IsTheStepTakenSTimesAboutTheCentre) {
  const Eigen::Vector3d c(0.3, -0.2, 2.0);
  const Isometry3 R = rotationAbout({0.2, 1.0, 0.1}, 0.03, c);
  const Isometry3 t = translation({0.01, -0.004, 0.002});
  for (const Isometry3& step : {R, t}) {
    EXPECT_LT(distance(stepPower(step, c, 0.0), Isometry3::Identity()), 1e-12);
    EXPECT_LT(distance(stepPower(step, c, 1.0), step), 1e-12);
    EXPECT_LT(distance(stepPower(step, c, 3.0), step * step * step), 1e-12);
    EXPECT_LT(distance(stepPower(step, c, -1.0), step.inverse()), 1e-12);
  }
  // A rotation about an axis away from the centre: the centre's displacement is scaled, the
  // rotation's angle too.
  const Isometry3 off = rotationAbout({0, 1, 0}, 0.02, c + Eigen::Vector3d(1, 0, 0));
  const Isometry3 twice = stepPower(off, c, 2.0);
  EXPECT_NEAR(Eigen::AngleAxisd(twice.linear()).angle(), 0.04, 1e-12);
  EXPECT_LT((twice * c - c - 2.0 * (off * c - c)).norm(), 1e-12);
}

TEST(StepExtrapolation, AGeometricIterationJumpsToItsLimit) {
  // x_{k+1} = x_k + (1 - r)(x* - x_k): each step is r times the one before and points the same
  // way; the rest of the series is r / (1 - r) times the last step.
  const auto points = cloudAround({0.1, 0.2, 2.5});
  const Eigen::Vector3d c = centreOf(points);
  for (const double r : {0.3, 0.6, 0.75}) {
    for (const bool rotate : {false, true}) {
      // The remaining error e as a motion; a step removes the share (1 - r) of it.
      const Isometry3 e0 = rotate ? rotationAbout({0.3, 1.0, -0.2}, 0.05, c) : translation({0.08, -0.03, 0.02});
      const Isometry3 A = stepPower(e0, c, 1.0 - r);          // first step
      const Isometry3 B = stepPower(e0, c, (1.0 - r) * r);    // second step
      // The points after A, where B and the jump apply.
      std::vector<Eigen::Vector3d> moved;
      for (const auto& p : points) moved.push_back(A * p);
      const StepExtrapolation x = extrapolateSteps(A, B, moved, 100.0);
      // Exact for the translation; for the rotation the displacements are chords, which grow
      // with sin(angle / 2), not the angle, and turn with it.
      const double tol = rotate ? 1e-3 : 1e-9;
      EXPECT_NEAR(x.cosine, 1.0, tol * 0.1) << r;
      EXPECT_NEAR(x.ratio, r, tol * r) << r;
      EXPECT_NEAR(x.factor, r / (1.0 - r), tol * 20.0) << r;
      // After A, B and the jump, nothing of e0 is left.
      EXPECT_LT(distance(x.jump * B * A, e0), tol) << r;
    }
  }
}

TEST(StepExtrapolation, IsCappedAndOnlyForStepsThatAgree) {
  const auto points = cloudAround({0, 0, 2});
  const Isometry3 a = translation({0.01, 0, 0});
  // Nearly converged: r / (1 - r) capped.
  const StepExtrapolation slow = extrapolateSteps(a, translation({0.009, 0, 0}), points, 4.0);
  EXPECT_DOUBLE_EQ(slow.factor, 4.0);
  EXPECT_LT(distance(slow.jump, translation({0.036, 0, 0})), 1e-12);
  // Steps that do not shrink (an iteration running into its basin, not converging): no jump.
  EXPECT_EQ(extrapolateSteps(a, translation({0.012, 0, 0}), points, 4.0).factor, 0.0);
  EXPECT_EQ(extrapolateSteps(a, a, points, 4.0).factor, 0.0);
  // Steps at right angles, or turning back (an overshoot): no jump.
  for (const Isometry3& b : {translation({0, 0.005, 0}), translation({-0.005, 0, 0}), translation({0.005, 0.004, 0})}) {
    const StepExtrapolation x = extrapolateSteps(a, b, points, 4.0);
    EXPECT_EQ(x.factor, 0.0);
    EXPECT_LT(distance(x.jump, Isometry3::Identity()), 1e-15);
  }
  // Off, no points, no motion, not finite: no jump.
  const Isometry3 half = translation({0.005, 0, 0});
  EXPECT_EQ(extrapolateSteps(a, half, points, 0.0).factor, 0.0);
  EXPECT_EQ(extrapolateSteps(a, half, {}, 4.0).factor, 0.0);
  EXPECT_EQ(extrapolateSteps(Isometry3::Identity(), a, points, 4.0).factor, 0.0);
  EXPECT_EQ(extrapolateSteps(a, Isometry3::Identity(), points, 4.0).factor, 0.0);
  Isometry3 nan = a;
  nan.translation().x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(extrapolateSteps(a, nan, points, 4.0).factor, 0.0);
  EXPECT_EQ(extrapolateSteps(nan, a, points, 4.0).factor, 0.0);
  EXPECT_EQ(extrapolateSteps(a, half, {Eigen::Vector3d(std::numeric_limits<double>::infinity(), 0, 0)}, 4.0).factor, 0.0);
}
