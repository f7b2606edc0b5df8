#pragma once
/// \file view_association.h Dense patch-to-patch associations between two views (paper III-E,
/// NOTES item 5): for each patch mu of view A, the C patches of view B nearest under a candidate
/// key (quantile signatures by default; the paper's KD-tree over feature-set means as an option)
/// are candidates; the one with the least restricted Damerau-Levenshtein distance D is the
/// putative partner (ties: lowest patch index), accepted when the normalised distance
/// D_hat = D / (k_S + k_S') is at most lambda. The distances are computed by the banded, sparse
/// algorithm of banded_distance.h (exactly osaDistance() with FeatureMatch), each with the bound
/// min(lambda, best so far) (k_S + k_S'). Optionally (default) only mutual best partners are
/// kept. Parallel over the patches; the result does not depend on the thread count.
#include <string>
#include <vector>

#include "gasp/association/edit_distance.h"
#include "gasp/association/feature_match.h"
#include "gasp/association/feature_sets.h"
#include "gasp/association/patch_geometry.h"

namespace gasp {

/// How the C candidates of a patch are chosen (the edit distance is then computed to each).
enum class CandidateKey {
  /// Paper: KD-tree over the feature-set means (each component divided by its match tolerance).
  kMean,
  /// Quantile signature: each component's values at 9 evenly spaced ranks, divided by the match
  /// tolerance, compared with the L1 distance (exhaustive search). Ranks the exact best partner
  /// higher than the mean (docs/association.md), so fewer candidates are needed.
  kQuantiles,
};

struct AssociationParams {
  /// Neighbourhoods, features and ordering. The neighbourhood default here is the k = 30
  /// nearest patches (the paper used full views; docs/association.md has the measurements).
  FeatureSetParams feature_sets = defaultFeatureSets();
  MatchParams match;   ///< r_dev = 0.04 m, theta_dev = 10 deg (paper)
  EditCosts costs;     ///< insert = delete = 1, replace disabled, transposition 0 (paper)
  /// C, candidates per patch, >= 1 (paper: 75, with the mean key). The quantile key ranks the
  /// best partner higher, so fewer candidates give the same precision and density in less time
  /// (docs/association.md).
  int candidates = 20;
  double lambda = 0.5;   ///< gating on D_hat, in [0, 1] (paper: 0.65 - 0.8 before RANSAC)
  /// Keep (a, b) only when a is also b's best partner in A (B -> A search over b's own C
  /// candidates, only for the patches of B chosen by some patch of A). Not in the paper; a
  /// one-way best partner is often a look-alike, so the check raises precision
  /// (docs/association.md).
  bool mutual_check = true;
  /// How the C candidates are chosen (paper: kMean). Last member: aggregate initialisation of the
  /// members before it is unchanged.
  CandidateKey candidate_key = CandidateKey::kQuantiles;
  /// Distinctiveness (Lowe's ratio test on D_hat, not in the paper): a patch's best partner is
  /// kept only when its D_hat is below distinctiveness_ratio times the second best D_hat among
  /// its candidates (exact ties are never distinct). 1 = off (default; the paper's rule).
  double distinctiveness_ratio = 1.0;

  static FeatureSetParams defaultFeatureSets() {
    FeatureSetParams p;
    p.neighbourhood.k = 30;
    return p;
  }
};

/// Throws gasp::Error naming the first invalid parameter.
void validate(const AssociationParams& params);

struct PatchAssociation {
  int a = -1;             ///< patch index in view A
  int b = -1;             ///< patch index in view B
  double distance = 0.0;  ///< D_hat, normalised edit distance in [0, 1]
};

struct AssociationStats {
  std::size_t patches_a = 0, patches_b = 0;
  std::size_t with_features_a = 0, with_features_b = 0;  ///< patches with a non-empty Q
  std::size_t comparisons = 0;        ///< edit distances computed (A -> B and mutual check)
  std::size_t cut_early = 0;          ///< of those, rejected by the bounds or early termination
  std::size_t comparisons_full = 0;   ///< comparisons an exhaustive search in both directions would make
  std::size_t gated_out = 0;          ///< patches of A with candidates but none within lambda
  std::size_t not_mutual = 0;         ///< A -> B partners dropped by the mutual check
  std::size_t ambiguous = 0;          ///< best partners dropped by the distinctiveness ratio
  /// Time [ms]: feature sets (associateViews only); "tree" = preparing both views for the search
  /// (prepared sets, signatures or KD-tree); matching = both searches.
  double features_ms = 0, tree_ms = 0, matching_ms = 0;
};

struct AssociationResult {
  std::vector<PatchAssociation> associations;  ///< sorted by patch of A
  /// With mutual_check: the A -> B best partners the check dropped (sorted by patch of A), a
  /// wider, less precise hypothesis set (the pipeline falls back to it when the mutual ones give
  /// no pose). Empty without mutual_check.
  std::vector<PatchAssociation> one_way;
  AssociationStats stats;
  std::string reason;  ///< why the result is empty, when it is
};

/// Associates the patches of two views.
AssociationResult associateViews(const std::vector<PatchGeometry>& a, const std::vector<PatchGeometry>& b,
                                 const AssociationParams& params = {});

/// The same from feature sets already computed with params.feature_sets (Q of every patch).
AssociationResult associateFeatureSets(const std::vector<std::vector<Feature>>& qa,
                                       const std::vector<std::vector<Feature>>& qb,
                                       const AssociationParams& params = {});

}  // namespace gasp
