#pragma once
// Test helpers: random patch sets, and a patch set moved rigidly (centroids and normals).
#include <Eigen/Geometry>

#include <random>
#include <vector>

#include "gasp/association/patch_geometry.h"

namespace gasp::test {

/// n patches scattered in a 3 x 2 x 2 m box with random unit normals (fixed seed).
inline std::vector<PatchGeometry> randomPatches(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<PatchGeometry> out;
  for (int i = 0; i < n; ++i) {
    PatchGeometry p;
    p.centroid = Eigen::Vector3d(1.5 * u(rng), u(rng), 2.0 + u(rng));
    p.normal = Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized();
    out.push_back(p);
  }
  return out;
}

inline std::vector<PatchGeometry> moved(const std::vector<PatchGeometry>& patches, const Eigen::Isometry3d& T) {
  auto out = patches;
  for (auto& p : out) {
    p.centroid = T * p.centroid;
    p.normal = T.linear() * p.normal;
  }
  return out;
}

}  // namespace gasp::test
