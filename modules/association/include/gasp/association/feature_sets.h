#pragma once
/// \file feature_sets.h Ordered feature sets Q_mu of all patches of a view (paper sections
/// III-B, III-C) and their distance (III-D).
#include <limits>
#include <vector>

#include "gasp/association/edit_distance.h"
#include "gasp/association/feature_match.h"
#include "gasp/association/feature_ordering.h"
#include "gasp/association/invariant_feature.h"
#include "gasp/association/neighbourhood.h"
#include "gasp/association/patch_geometry.h"

namespace gasp {

/// Everything that defines Q_mu.
struct FeatureSetParams {
  NeighbourhoodParams neighbourhood;
  FeatureParams feature;
  OrderingParams ordering;
};

/// Throws gasp::Error when any part is invalid.
void validate(const FeatureSetParams& params);

/// Q_mu: q(mu, alpha) for alpha in `neighbours` (mu itself and neighbours giving no feature, see
/// computeFeature(), are skipped), sorted with sortFeatures(). Empty when mu is not usable.
std::vector<Feature> computeFeatureSet(const std::vector<PatchGeometry>& patches, int mu,
                                       const std::vector<int>& neighbours,
                                       const FeatureParams& feature_params = {},
                                       const OrderingParams& ordering_params = {});

/// Q_mu for every patch of a view (index = patch index): findNeighbourhoods() then
/// computeFeatureSet(). Never throws for bad patches (they get an empty set); validates params.
std::vector<std::vector<Feature>> computeFeatureSets(const std::vector<PatchGeometry>& patches,
                                                     const FeatureSetParams& params = {});

/// D_RDL(Q, Q'): osaDistance() with FeatureMatch; kExceedsBound when above `bound`.
inline double featureSetDistance(const std::vector<Feature>& q, const std::vector<Feature>& q_prime,
                                 const MatchParams& match_params, const EditCosts& costs,
                                 double bound, EditDistanceWorkspace& ws) {
  return osaDistance(q, q_prime, FeatureMatch{match_params}, costs, bound, ws);
}

}  // namespace gasp
