// Pose helpers: the RMS displacement of a point set between two poses, from the set's moments,
// equals the sum over the points.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "gasp/core/pose.h"

namespace {

using namespace gasp;

TEST(Pose, RmsDisplacementFromMomentsEqualsTheSumOverThePoints) {
  std::mt19937 rng(3);
  std::normal_distribution<double> g(0.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<Eigen::Vector3d> points;
    for (int i = 0; i < 50; ++i) points.emplace_back(g(rng), g(rng), 2.0 + g(rng));
    const auto pose = [&] {
      const Eigen::Quaterniond q(g(rng), g(rng), g(rng), g(rng));
      return Isometry3(Eigen::Translation3d(g(rng), g(rng), g(rng)) * q.normalized());
    };
    const Isometry3 a = pose(), b = pose();
    double sum = 0.0;
    for (const auto& p : points) sum += (a * p - b * p).squaredNorm();
    EXPECT_NEAR(rmsDisplacement(a, b, pointSpread(points)), std::sqrt(sum / points.size()), 1e-9);
    EXPECT_NEAR(rmsDisplacement(a, a, pointSpread(points)), 0.0, 1e-7);
  }
  EXPECT_EQ(pointSpread({}).mean, Eigen::Vector3d::Zero());
}

}  // namespace
