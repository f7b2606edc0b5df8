#include "gasp/association/neighbourhood.h"

#include <nanoflann.hpp>
#include <tbb/parallel_for.h>

#include <cstdint>
#include <string>

#include "gasp/core/error.h"

namespace gasp {
namespace {

/// nanoflann dataset adaptor over the centroids of the usable patches.
struct CentroidCloud {
  const std::vector<PatchGeometry>* patches = nullptr;
  std::vector<int> ids;  ///< usable patch index per KD-tree point

  std::size_t kdtree_get_point_count() const { return ids.size(); }
  double kdtree_get_pt(std::size_t idx, std::size_t dim) const {
    return (*patches)[static_cast<std::size_t>(ids[idx])].centroid[static_cast<Eigen::Index>(dim)];
  }
  template <class BBox>
  bool kdtree_get_bbox(BBox& /*bb*/) const {
    return false;
  }
};

using CentroidTree = nanoflann::KDTreeSingleIndexAdaptor<
    nanoflann::L2_Simple_Adaptor<double, CentroidCloud>, CentroidCloud, 3, std::uint32_t>;

}  // namespace

void validate(const NeighbourhoodParams& params) {
  if (params.k < 0) throw Error("NeighbourhoodParams::k must be >= 0 (0 = full view), got " + std::to_string(params.k));
}

std::vector<std::vector<int>> findNeighbourhoods(const std::vector<PatchGeometry>& patches,
                                                 const NeighbourhoodParams& params) {
  validate(params);
  std::vector<std::vector<int>> out(patches.size());
  CentroidCloud cloud;
  cloud.patches = &patches;
  for (std::size_t i = 0; i < patches.size(); ++i) {
    if (isUsable(patches[i])) cloud.ids.push_back(static_cast<int>(i));
  }
  const std::size_t usable = cloud.ids.size();
  if (usable < 2) return out;

  const auto k = static_cast<std::size_t>(params.k);
  if (k == 0 || k >= usable - 1) {  // full view
    for (const int mu : cloud.ids) {
      auto& nb = out[static_cast<std::size_t>(mu)];
      nb.reserve(usable - 1);
      for (const int alpha : cloud.ids) {
        if (alpha != mu) nb.push_back(alpha);
      }
    }
    return out;
  }

  const CentroidTree tree(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(10));
  // Independent queries: parallel (each writes its own neighbourhood).
  tbb::parallel_for(std::size_t{0}, usable, [&](std::size_t u) {
    const int mu = cloud.ids[u];
    std::vector<std::uint32_t> idx(k + 1);
    std::vector<double> dist2(k + 1);
    const Eigen::Vector3d& q = patches[static_cast<std::size_t>(mu)].centroid;
    const std::size_t found = tree.knnSearch(q.data(), k + 1, idx.data(), dist2.data());
    auto& nb = out[static_cast<std::size_t>(mu)];
    nb.reserve(k);
    // mu itself is among the k + 1 results unless k + 1 other patches share its centroid.
    for (std::size_t r = 0; r < found && nb.size() < k; ++r) {
      const int alpha = cloud.ids[idx[r]];
      if (alpha != mu) nb.push_back(alpha);
    }
  });
  return out;
}

}  // namespace gasp
