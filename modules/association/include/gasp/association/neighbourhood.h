#pragma once
/// \file neighbourhood.h Neighbourhood of each patch (paper section III-B/III-E, NOTES item 5):
/// the k nearest patches in 3D (KD-tree over centroids) or the full view.
#include <vector>

#include "gasp/association/patch_geometry.h"

namespace gasp {

/// Neighbourhood size.
struct NeighbourhoodParams {
  /// k nearest patches (by centroid distance in 3D). 0 = full view: every other patch (the
  /// paper's experiments, k = |S| - 1, about 750 patches per view). Must be >= 0.
  int k = 0;
};

/// Throws gasp::Error when k < 0.
void validate(const NeighbourhoodParams& params);

/// neighbours[mu]: indices of the patches in the neighbourhood of mu, never mu itself. With k > 0:
/// the min(k, usable - 1) nearest usable patches, nearest first (ties in any order). Full view:
/// every other usable patch in index order. Patches that are not isUsable() have an empty
/// neighbourhood and are in no neighbourhood. Validates params.
std::vector<std::vector<int>> findNeighbourhoods(const std::vector<PatchGeometry>& patches,
                                                 const NeighbourhoodParams& params = {});

}  // namespace gasp
