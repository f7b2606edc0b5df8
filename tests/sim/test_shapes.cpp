// Ray-primitive intersections against hand-computed values.
#include <gtest/gtest.h>

#include <cmath>

#include "gasp/sim/shapes.h"

using gasp::sim::RayHit;
using V = Eigen::Vector3d;

namespace {
constexpr double kEps = 1e-12;
}

TEST(SimShapes, RectangleHitAndMiss) {
  const gasp::sim::Rectangle r{1.0, 0.5};
  RayHit hit;
  // From (0.5, 0.2, -2) straight up +z: hits z = 0 at t = 2.
  ASSERT_TRUE(intersect(r, V(0.5, 0.2, -2.0), V(0, 0, 1), 1e-6, hit));
  EXPECT_NEAR(hit.t, 2.0, kEps);
  EXPECT_NEAR(hit.normal.z(), 1.0, kEps);
  // Non-unit oblique direction: o + t d with d = (0.25, 0, 0.5) from z = -1 -> t = 2, x = 0.5.
  ASSERT_TRUE(intersect(r, V(0, 0, -1), V(0.25, 0, 0.5), 1e-6, hit));
  EXPECT_NEAR(hit.t, 2.0, kEps);
  EXPECT_FALSE(intersect(r, V(0, 0.6, -1), V(0, 0, 1), 1e-6, hit));  // outside |y| <= 0.5
  EXPECT_FALSE(intersect(r, V(0, 0, -1), V(1, 0, 0), 1e-6, hit));    // parallel
  EXPECT_FALSE(intersect(r, V(0, 0, 1), V(0, 0, 1), 1e-6, hit));     // behind
}

TEST(SimShapes, BoxFacesAndInside) {
  const gasp::sim::Box b{V(1.0, 2.0, 3.0)};
  RayHit hit;
  ASSERT_TRUE(intersect(b, V(-5, 0, 0), V(1, 0, 0), 1e-6, hit));  // enters through -x
  EXPECT_NEAR(hit.t, 4.0, kEps);
  EXPECT_EQ(hit.face, 0);
  EXPECT_NEAR(hit.normal.x(), -1.0, kEps);
  ASSERT_TRUE(intersect(b, V(0, 0, 10), V(0, 0, -2), 1e-6, hit));  // +z face, non-unit dir
  EXPECT_NEAR(hit.t, 3.5, kEps);
  EXPECT_EQ(hit.face, 5);
  ASSERT_TRUE(intersect(b, V(0.5, 9, 0), V(0, -1, 0), 1e-6, hit));  // +y face
  EXPECT_NEAR(hit.t, 7.0, kEps);
  EXPECT_EQ(hit.face, 3);
  ASSERT_TRUE(intersect(b, V(0, 0, 0), V(0, -1, 0), 1e-6, hit));  // from inside: exit face -y
  EXPECT_NEAR(hit.t, 2.0, kEps);
  EXPECT_EQ(hit.face, 2);
  EXPECT_FALSE(intersect(b, V(-5, 2.5, 0), V(1, 0, 0), 1e-6, hit));
}

TEST(SimShapes, CylinderSideAndCaps) {
  const gasp::sim::Cylinder c{0.5, 1.0};
  RayHit hit;
  ASSERT_TRUE(intersect(c, V(-3, 0, 0.2), V(1, 0, 0), 1e-6, hit));
  EXPECT_NEAR(hit.t, 2.5, kEps);
  EXPECT_EQ(hit.face, 0);
  EXPECT_NEAR(hit.normal.x(), -1.0, kEps);
  // Off-centre side hit: y = 0.3 -> x = -0.4, t = 2.6.
  ASSERT_TRUE(intersect(c, V(-3, 0.3, 0), V(1, 0, 0), 1e-6, hit));
  EXPECT_NEAR(hit.t, 2.6, kEps);
  EXPECT_NEAR(hit.normal.y(), 0.6, 1e-12);
  ASSERT_TRUE(intersect(c, V(0.1, 0.1, 5), V(0, 0, -1), 1e-6, hit));  // top cap
  EXPECT_NEAR(hit.t, 4.0, kEps);
  EXPECT_EQ(hit.face, 2);
  ASSERT_TRUE(intersect(c, V(0.1, 0.1, -5), V(0, 0, 1), 1e-6, hit));  // bottom cap
  EXPECT_EQ(hit.face, 1);
  EXPECT_NEAR(hit.normal.z(), -1.0, kEps);
  EXPECT_FALSE(intersect(c, V(-3, 0, 1.2), V(1, 0, 0), 1e-6, hit));  // above the top
  EXPECT_FALSE(intersect(c, V(0.6, 0, 5), V(0, 0, -1), 1e-6, hit));  // outside the caps
}

TEST(SimShapes, Sphere) {
  const gasp::sim::Sphere s{1.0};
  RayHit hit;
  ASSERT_TRUE(intersect(s, V(0, 0, -4), V(0, 0, 2), 1e-6, hit));
  EXPECT_NEAR(hit.t, 1.5, kEps);
  EXPECT_NEAR(hit.normal.z(), -1.0, kEps);
  // Ray at x = 0.6: hits z = -0.8.
  ASSERT_TRUE(intersect(s, V(0.6, 0, -4), V(0, 0, 1), 1e-6, hit));
  EXPECT_NEAR(hit.t, 3.2, 1e-12);
  EXPECT_NEAR(hit.normal.x(), 0.6, 1e-12);
  ASSERT_TRUE(intersect(s, V(0, 0, 0), V(1, 0, 0), 1e-6, hit));  // from inside
  EXPECT_NEAR(hit.t, 1.0, kEps);
  EXPECT_FALSE(intersect(s, V(1.1, 0, -4), V(0, 0, 1), 1e-6, hit));
}

TEST(SimShapes, RoomInwardFaces) {
  const gasp::sim::Room r{V(4, 3, 1.5)};
  RayHit hit;
  ASSERT_TRUE(intersect(r, V(1, 0, 0), V(0, 0, -1), 1e-6, hit));  // floor
  EXPECT_NEAR(hit.t, 1.5, kEps);
  EXPECT_EQ(hit.face, 4);
  EXPECT_NEAR(hit.normal.z(), 1.0, kEps);  // inward
  ASSERT_TRUE(intersect(r, V(1, 0, 0), V(1, 0, 0), 1e-6, hit));  // wall +x
  EXPECT_NEAR(hit.t, 3.0, kEps);
  EXPECT_EQ(hit.face, 1);
  EXPECT_NEAR(hit.normal.x(), -1.0, kEps);
  EXPECT_EQ(gasp::sim::faceName(r, 4), "floor");
}

TEST(SimShapes, FaceCountsAndBounds) {
  EXPECT_EQ(gasp::sim::faceCount(gasp::sim::Box{}), 6);
  EXPECT_EQ(gasp::sim::faceCount(gasp::sim::Cylinder{}), 3);
  EXPECT_EQ(gasp::sim::faceCount(gasp::sim::Sphere{}), 1);
  EXPECT_NEAR(gasp::sim::boundingRadius(gasp::sim::Box{V(1, 2, 2)}), 3.0, kEps);
  EXPECT_TRUE(std::isinf(gasp::sim::boundingRadius(gasp::sim::Room{})));
}
