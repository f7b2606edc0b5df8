// Place descriptors (place_descriptor.h) on the simulator's room: the same for a rigidly moved
// view, nearly the same for the same place seen rolled by 180 degrees, farther for other places;
// and the index's nearest-first search.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "gasp/association/place_descriptor.h"
#include "gasp/association/view_association.h"
#include "gasp/core/error.h"
#include "synthetic_pairs.h"

namespace {

using namespace gasp;
using namespace gasp::test;

std::vector<PatchGeometry> patchesOf(int frame) {
  const auto& s = simulation("room");
  return toPatchGeometry(makeDepthView(s.frame(frame).depth, sim::SimulationOptions{}.intrinsics).segmentation.patches);
}

PlaceDescriptor describe(const std::vector<PatchGeometry>& patches) {
  return describePlace(computeFeatureSets(patches, AssociationParams{}.feature_sets));
}

TEST(PlaceDescriptor, ARigidlyMovedViewHasTheSameDescriptor) {
  const std::vector<PatchGeometry> patches = patchesOf(10);
  const PlaceDescriptor d = describe(patches);
  ASSERT_GT(d.features, 1000u);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 5; ++trial) {
    const Eigen::Vector3d axis = Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized();
    const Isometry3 T = Eigen::Translation3d(u(rng), u(rng), u(rng)) * Eigen::AngleAxisd(3.0 * u(rng), axis);
    std::vector<PatchGeometry> moved = patches;
    for (PatchGeometry& p : moved) {
      p.centroid = T * p.centroid;
      p.normal = T.linear() * p.normal;
    }
    const PlaceDescriptor m = describe(moved);
    EXPECT_EQ(m.features, d.features);
    // The features agree to rounding; one may cross a bin edge.
    EXPECT_LT(placeDistance(d, m), 0.01) << trial;
  }
}

TEST(PlaceDescriptor, TheSamePlaceRolledIsNearerThanOtherPlaces) {
  // The room's last segment rolls the camera 0 -> 180 deg about its axis, standing still (frames
  // 44-59); frames 0 and 25 look elsewhere (docs/simulator.md).
  const PlaceDescriptor start = describe(patchesOf(44)), rolled = describe(patchesOf(59));
  const double same = placeDistance(start, rolled);
  std::printf("room: 44 -> 59 (rolled 180 deg) %.3f", same);
  for (const int other : {0, 10, 25}) {
    const double d = placeDistance(start, describe(patchesOf(other)));
    std::printf(", 44 -> %d %.3f", other, d);
    EXPECT_LT(same, d) << other;
  }
  std::printf("\n");
}

TEST(PlaceIndex, NearestFirstWithExclusions) {
  PlaceDescriptorParams p;
  p.distance_edges_m = {1.0};
  p.angle_bins = 1;  // two bins: shorter and longer than 1 m
  const auto place = [&](int near, int far) {
    std::vector<std::vector<Feature>> sets(1);
    for (int i = 0; i < near; ++i) sets[0].push_back({0, 0, 0, 0.5, 1, 1, 1});
    for (int i = 0; i < far; ++i) sets[0].push_back({0, 0, 0, 2.0, 1, 1, 1});
    return describePlace(sets, p);
  };
  PlaceIndex index;
  EXPECT_TRUE(index.add(7, place(10, 0)));
  EXPECT_TRUE(index.add(3, place(5, 5)));
  EXPECT_TRUE(index.add(9, place(0, 10)));
  EXPECT_TRUE(index.add(4, place(10, 0)));  // the same as 7: ties go by id
  EXPECT_FALSE(index.add(5, PlaceDescriptor{}));
  EXPECT_EQ(index.size(), 4u);
  const auto all = index.query(place(9, 1), 10);
  ASSERT_EQ(all.size(), 4u);
  EXPECT_EQ(all[0].first, 4u);
  EXPECT_EQ(all[1].first, 7u);
  EXPECT_EQ(all[2].first, 3u);
  EXPECT_EQ(all[3].first, 9u);
  EXPECT_NEAR(placeDistance(place(10, 0), place(0, 10)), 1.0, 1e-6);  // nothing in common
  EXPECT_NEAR(placeDistance(place(10, 0), place(20, 0)), 0.0, 1e-6);  // the same distribution
  const auto top = index.query(place(9, 1), 2, [](std::size_t id) { return id == 4; });
  ASSERT_EQ(top.size(), 2u);
  EXPECT_EQ(top[0].first, 7u);
  EXPECT_EQ(top[1].first, 3u);
  EXPECT_TRUE(index.query(PlaceDescriptor{}, 3).empty());
  PlaceDescriptorParams other;
  EXPECT_THROW(placeDistance(place(1, 1), describePlace({{{0, 0, 0, 0.5, 1, 1, 1}}}, other)), Error);
  other.distance_edges_m = {0.5, 0.2};
  EXPECT_THROW(validate(other), Error);
  other = {};
  other.angle_bins = 0;
  EXPECT_THROW(validate(other), Error);
}

}  // namespace
