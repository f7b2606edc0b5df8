#pragma once
// Test helper: a patch set moved rigidly (centroids and normals).
#include <Eigen/Geometry>

#include <vector>

#include "gasp/association/patch_geometry.h"

namespace gasp::test {

inline std::vector<PatchGeometry> moved(const std::vector<PatchGeometry>& patches, const Eigen::Isometry3d& T) {
  auto out = patches;
  for (auto& p : out) {
    p.centroid = T * p.centroid;
    p.normal = T.linear() * p.normal;
  }
  return out;
}

}  // namespace gasp::test
