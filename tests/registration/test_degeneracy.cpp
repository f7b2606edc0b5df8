// Degeneracy: one plane or two parallel planes leave three directions unobservable, two
// non-parallel planes one (the translation along their intersection); a room corner none. A
// degenerate estimate is never claimed.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "gasp/core/error.h"
#include "gasp/registration/degeneracy.h"
#include "gasp/registration/refinement.h"
#include "synthetic_scene.h"

namespace {

using namespace gasp;
using namespace gasp::test;

RegistrationResult refineNoisy(const std::vector<Plane>& planes, const Isometry3& T) {
  SceneOptions o;
  o.centroid_sigma_m = 0.005;
  o.normal_sigma_deg = 2.0;
  const Scene s = makeScene(planes, T, o);
  return refinePose(s.correspondences, T);
}

/// |cos| of the angle between a direction's translation (or rotation) part and an axis.
double alignment(const RegistrationResult& r, int column, bool rotation, const Eigen::Vector3d& axis) {
  const Vector6d d = r.unobservable_directions.col(column);
  return std::abs((rotation ? d.tail<3>() : d.head<3>()).normalized().dot(axis));
}

int count(const std::string& text, const std::string& what) {
  int n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST(Degeneracy, OnePlaneLeavesTwoTranslationsAndTheRotationAboutItsNormal) {
  const std::vector<Plane> wall = {plane({0.3, -0.2, 3.0}, {0, 0, -1}, 1.5, 1.0)};
  const RegistrationResult r = refineNoisy(wall, testMotions()[1]);
  EXPECT_TRUE(r.degenerate);
  EXPECT_FALSE(r.success);
  EXPECT_EQ(r.unobservable_directions.cols(), 3);
  EXPECT_EQ(count(r.reason, "translation along"), 2) << r.reason;
  EXPECT_EQ(count(r.reason, "rotation about"), 1) << r.reason;
  // The normal stays along target z after the 180-degree roll: in-plane translations, rotation about z.
  for (int j = 0; j < 2; ++j) EXPECT_LT(alignment(r, j, false, Eigen::Vector3d::UnitZ()), 0.05) << r.reason;
  EXPECT_GT(alignment(r, 2, true, Eigen::Vector3d::UnitZ()), std::cos(3 * M_PI / 180)) << r.reason;
}

TEST(Degeneracy, TwoParallelPlanesAreDegenerateToo) {
  // A corridor: two walls facing each other.
  const std::vector<Plane> corridor = {plane({-1.0, 0.0, 3.0}, {1, 0, 0}, 2.0, 1.0),
                                       plane({1.0, 0.0, 3.0}, {-1, 0, 0}, 2.0, 1.0)};
  const RegistrationResult r = refineNoisy(corridor, Isometry3::Identity());
  EXPECT_TRUE(r.degenerate);
  EXPECT_FALSE(r.success);
  EXPECT_EQ(r.unobservable_directions.cols(), 3) << r.reason;
  EXPECT_EQ(count(r.reason, "translation along"), 2) << r.reason;
  for (int j = 0; j < 2; ++j) EXPECT_LT(alignment(r, j, false, Eigen::Vector3d::UnitX()), 0.05) << r.reason;
  EXPECT_GT(alignment(r, 2, true, Eigen::Vector3d::UnitX()), std::cos(3 * M_PI / 180)) << r.reason;
}

TEST(Degeneracy, TwoNonParallelPlanesLeaveTheTranslationAlongTheirIntersection) {
  // Point-to-plane residuals cannot see a slide along the floor/wall edge (here x).
  const auto corner = roomCorner();
  const RegistrationResult r = refineNoisy({corner[0], corner[1]}, Isometry3::Identity());
  EXPECT_TRUE(r.degenerate);
  EXPECT_EQ(r.unobservable_directions.cols(), 1) << r.reason;
  EXPECT_EQ(count(r.reason, "translation along"), 1) << r.reason;
  EXPECT_GT(alignment(r, 0, false, Eigen::Vector3d::UnitX()), std::cos(3 * M_PI / 180)) << r.reason;
}

TEST(Degeneracy, ARoomCornerIsWellConditioned) {
  for (const Isometry3& T : testMotions()) {
    const RegistrationResult r = refineNoisy(roomCorner(), T);
    EXPECT_FALSE(r.degenerate) << r.reason;
    EXPECT_TRUE(r.success);
    EXPECT_EQ(r.unobservable_directions.cols(), 0);
    EXPECT_GT(r.information_eigenvalues(0), 0.05 * r.information_eigenvalues(5));
  }
}

TEST(Degeneracy, ASceneFarFromTheCameraIsConditionedAboutItsCentre) {
  // The room corner 20 m away: rotations about the camera would be nearly translations (lever
  // arm 20 m) and look degenerate; about the scene centre they are well conditioned.
  Matrix6d I = Matrix6d::Zero();
  std::vector<Eigen::Vector3d> points;
  const std::vector<Plane> corner = roomCorner();
  std::mt19937 rng(2);
  for (int i = 0; i < 90; ++i) {
    const Patch p = randomPatch(corner, rng);
    const Eigen::Vector3d x = p.point + Eigen::Vector3d(0, 0, 20);
    Vector6d j;
    j << p.on->normal, x.cross(p.on->normal);  // d r / d [rho; omega] for r = n . (x - q)
    I += j * j.transpose() * 1e4;
    points.push_back(x);
  }
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (const auto& x : points) c += x / 90.0;
  double sq = 0.0;
  for (const auto& x : points) sq += (x - c).squaredNorm() / 90.0;
  const DegeneracyAnalysis a = analyseDegeneracy(I, c, std::sqrt(sq));
  EXPECT_FALSE(a.degenerate) << a.reason;
  EXPECT_GT(a.eigenvalues(0), 0.05 * a.eigenvalues(5));
  EXPECT_TRUE(analyseDegeneracy(I, Eigen::Vector3d::Zero(), std::sqrt(sq)).degenerate);
}

TEST(Degeneracy, NamesTheRotationAboutAPlaneNormalWithoutCoupling) {
  // A plane off the optical axis (normal z through c = (2, 1, 5)): the unobservable rotation
  // about its normal is reported as a pure rotation.
  const Eigen::Vector3d c(2.0, 1.0, 5.0), n(0, 0, 1);
  Matrix6d I = Matrix6d::Zero();
  for (double u : {-1.0, 0.0, 1.0})
    for (double v : {-1.0, 0.0, 1.0}) {
      const Eigen::Vector3d x = c + Eigen::Vector3d(u, v, 0.0);
      Vector6d j;
      j << n, x.cross(n);  // d r / d [rho; omega] for r = n . (x - q)
      I += j * j.transpose() * 1e4;
    }
  const DegeneracyAnalysis a = analyseDegeneracy(I, c, 0.8);
  ASSERT_TRUE(a.degenerate);
  ASSERT_EQ(a.unobservable_directions.cols(), 3);
  EXPECT_NEAR(std::abs(a.unobservable_directions(5, 2)), 1.0, 1e-9);  // last: the pure rotation about z
  EXPECT_NE(a.reason.find("rotation about (0.00, 0.00, 1.00)"), std::string::npos) << a.reason;
  EXPECT_EQ(a.reason.find("with"), std::string::npos) << a.reason;  // no coupled directions
  EXPECT_NEAR(a.eigenvalues(0), 0.0, 1e-6);
}

TEST(Degeneracy, AbsoluteFloorFlagsWeakInformation) {
  DegeneracyParams p;
  p.max_std_m = 0.05;  // lambda must reach 400 / m^2
  Matrix6d I = Matrix6d::Identity() * 1000.0;
  EXPECT_FALSE(analyseDegeneracy(I, Eigen::Vector3d::Zero(), 1.0, p).degenerate);
  I(0, 0) = 300.0;  // ratio 0.3 is fine, but the x standard deviation is 5.8 cm
  const DegeneracyAnalysis a = analyseDegeneracy(I, Eigen::Vector3d::Zero(), 1.0, p);
  EXPECT_TRUE(a.degenerate);
  EXPECT_NE(a.reason.find("translation along (1.00, 0.00, 0.00)"), std::string::npos) << a.reason;
  p.max_std_m = 0.0;
  EXPECT_THROW(validate(p), gasp::Error);
}

}  // namespace
