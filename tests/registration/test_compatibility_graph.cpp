// The compatibility graph behind RANSAC's guided sampling: adjacency equals its definition, the
// sampler only returns triangles, and its all-inlier probability matches the draw frequencies.
#include <gtest/gtest.h>

#include <cmath>

#include "compatibility_graph.h"  // private: this target has modules/registration/src on its path
#include "gasp/registration/inlier_criterion.h"
#include "synthetic_scene.h"

namespace {

using namespace gasp;
using namespace gasp::test;

double angle(const Eigen::Vector3d& a, const Eigen::Vector3d& b) { return std::acos(std::clamp(a.dot(b), -1.0, 1.0)); }

Scene noisyScene(int n, double outliers, unsigned seed) {
  SceneOptions o;
  o.n = n;
  o.outlier_fraction = outliers;
  o.centroid_sigma_m = 0.005;
  o.normal_sigma_deg = 2.0;
  o.seed = seed;
  return makeScene(roomCorner(), testMotions()[2], o);
}

TEST(CompatibilityGraph, AdjacencyIsTheDefinition) {
  const Scene s = noisyScene(150, 0.5, 3);
  const auto& c = s.correspondences;
  const double tol = 20.0 * M_PI / 180.0;
  const detail::CompatibilityGraph g(c, 0.03, tol);
  int edges = 0;
  for (int i = 0; i < g.size(); ++i) {
    int degree = 0;
    for (int j = 0; j < g.size(); ++j) {
      const auto& a = c[static_cast<std::size_t>(i)];
      const auto& b = c[static_cast<std::size_t>(j)];
      const double ds = (a.p_source - b.p_source).norm(), dt = (a.p_target - b.p_target).norm();
      const double da = std::abs(angle(a.n_source, b.n_source) - angle(a.n_target, b.n_target));
      const bool expected = i != j && ds > 0 && dt > 0 && std::abs(ds - dt) <= 0.03 && da <= tol + 1e-9;
      const bool borderline = std::abs(da - tol) < 1e-6;  // cos vs acos rounding
      if (!borderline) {
        EXPECT_EQ(g.adjacent(i, j), expected) << i << " " << j;
      }
      EXPECT_EQ(g.adjacent(i, j), g.adjacent(j, i));
      degree += g.adjacent(i, j);
    }
    EXPECT_EQ(degree, g.degree(i));
    edges += degree;
  }
  EXPECT_GT(edges, 0);
}

TEST(CompatibilityGraph, DrawsTrianglesWithTheStatedProbability) {
  const Scene s = noisyScene(120, 0.6, 11);
  const detail::CompatibilityGraph g(s.correspondences, 0.03, 20.0 * M_PI / 180.0);
  std::vector<int> inliers = selectInliers(s.correspondences, testMotions()[2], {});
  ASSERT_GT(inliers.size(), 20u);
  std::vector<bool> in(s.correspondences.size(), false);
  for (int i : inliers) in[static_cast<std::size_t>(i)] = true;
  std::mt19937 rng(1);
  const int draws = 200000;
  int all_in = 0;
  for (int d = 0; d < draws; ++d) {
    int i, j, k;
    if (!g.drawTriangle(rng, i, j, k)) continue;
    ASSERT_TRUE(g.adjacent(i, j) && g.adjacent(i, k) && g.adjacent(j, k));
    all_in += in[static_cast<std::size_t>(i)] && in[static_cast<std::size_t>(j)] && in[static_cast<std::size_t>(k)];
  }
  const double p = g.probabilityAllIn(inliers);
  const double sigma = std::sqrt(p * (1 - p) / draws);
  EXPECT_NEAR(static_cast<double>(all_in) / draws, p, 4 * sigma + 1e-4);
  // Far above the uniform rate e^3: the point of the sampler.
  const double e = static_cast<double>(inliers.size()) / static_cast<double>(s.correspondences.size());
  EXPECT_GT(p, 3 * e * e * e);
  EXPECT_EQ(g.probabilityAllIn({}), 0.0);
}

TEST(CompatibilityGraph, NoCompatiblePairsNoSeeds) {
  std::vector<PatchCorrespondence> c(3);
  c[0].p_source = {0, 0, 1};  c[0].p_target = {0, 0, 1};
  c[1].p_source = {1, 0, 1};  c[1].p_target = {0, 3, 1};
  c[2].p_source = {0, 1, 1};  c[2].p_target = {5, 0, 1};
  const detail::CompatibilityGraph g(c, 0.03, 0.3);
  EXPECT_TRUE(g.seeds().empty());
  EXPECT_EQ(g.degree(0), 0);
}

}  // namespace
