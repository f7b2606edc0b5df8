#pragma once
/// \file patch_geometry.h The only geometry of a surface patch the association stage uses.
#include <Eigen/Core>

#include <vector>

namespace gasp {

/// Location and orientation of one surface patch (paper section III-B: l_mu and n_mu), in the
/// frame of its view. Plain data so that the association module does not depend on how the
/// patches were made.
struct PatchGeometry {
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();  ///< l_mu, patch location [m]
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();    ///< n_mu, unit normal (normalised again on use)
};

/// True when the centroid is finite and the normal finite and non-zero: only such patches get
/// features and appear in neighbourhoods.
inline bool isUsable(const PatchGeometry& p) {
  return p.centroid.allFinite() && p.normal.allFinite() && p.normal.squaredNorm() > 1e-24;
}

/// Geometry of any patch type with members `centroid` and `normal` (e.g. gasp::SurfacePatch from
/// gasp/superpixels/surface_patch.h), without making this module depend on it.
template <class Patch>
std::vector<PatchGeometry> toPatchGeometry(const std::vector<Patch>& patches) {
  std::vector<PatchGeometry> out;
  out.reserve(patches.size());
  for (const auto& p : patches) out.push_back(PatchGeometry{p.centroid, p.normal});
  return out;
}

}  // namespace gasp
