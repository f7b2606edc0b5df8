#include "gasp/pipeline/associate_stage.h"

#include <tbb/parallel_invoke.h>

#include <chrono>

#include "gasp/core/stopwatch.h"

namespace gasp {

AssociatedViews associate(const DepthView& source, const DepthView& target, const AssociationParams& params) {
  validate(params);
  const auto t0 = std::chrono::steady_clock::now();
  AssociatedViews a;
  a.params = params;
  a.source_patches = toPatchGeometry(source.segmentation.patches);
  a.target_patches = toPatchGeometry(target.segmentation.patches);
  tbb::parallel_invoke([&] { a.source_features = computeFeatureSets(a.source_patches, params.feature_sets); },
                       [&] { a.target_features = computeFeatureSets(a.target_patches, params.feature_sets); });
  const double features_ms = msSince(t0);
  a.result = associateFeatureSets(a.source_features, a.target_features, params);
  a.result.stats.features_ms = features_ms;
  a.ms = msSince(t0);
  return a;
}

}  // namespace gasp
