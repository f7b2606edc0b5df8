#include "gasp/association/feature_sets.h"

#include <tbb/parallel_for.h>

#include <string>

#include "gasp/core/error.h"

namespace gasp {

void validate(const FeatureSetParams& params) {
  validate(params.neighbourhood);
  validate(params.feature);
  validate(params.ordering);
}

std::vector<Feature> computeFeatureSet(const std::vector<PatchGeometry>& patches, int mu,
                                       const std::vector<int>& neighbours,
                                       const FeatureParams& feature_params,
                                       const OrderingParams& ordering_params) {
  std::vector<Feature> q;
  if (mu < 0 || static_cast<std::size_t>(mu) >= patches.size()) {
    throw Error("computeFeatureSet: patch index " + std::to_string(mu) + " out of range [0, " +
                std::to_string(patches.size()) + ")");
  }
  const PatchGeometry& p = patches[static_cast<std::size_t>(mu)];
  if (!isUsable(p)) return q;
  q.reserve(neighbours.size());
  for (const int alpha : neighbours) {
    if (alpha == mu || alpha < 0 || static_cast<std::size_t>(alpha) >= patches.size()) continue;
    if (auto f = computeFeature(p, patches[static_cast<std::size_t>(alpha)], feature_params)) {
      q.push_back(*f);
    }
  }
  sortFeatures(q, ordering_params);
  return q;
}

std::vector<std::vector<Feature>> computeFeatureSets(const std::vector<PatchGeometry>& patches,
                                                     const FeatureSetParams& params) {
  validate(params);
  const auto neighbourhoods = findNeighbourhoods(patches, params.neighbourhood);
  std::vector<std::vector<Feature>> sets(patches.size());
  // Independent per patch: parallel, and the result does not depend on the thread count.
  tbb::parallel_for(std::size_t{0}, patches.size(), [&](std::size_t mu) {
    sets[mu] = computeFeatureSet(patches, static_cast<int>(mu), neighbourhoods[mu], params.feature,
                                 params.ordering);
  });
  return sets;
}

}  // namespace gasp
