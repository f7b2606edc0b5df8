#pragma once
/// \file view_association.h Dense patch-to-patch associations between two views (paper III-E,
/// NOTES item 5): for each patch mu of view A, the C patches of view B whose normalised
/// feature-set means are nearest (KD-tree) are candidates; the one with the least restricted
/// Damerau-Levenshtein distance D is the putative partner, accepted when the normalised distance
/// D_hat = D / (k_S + k_S') is at most lambda. Early termination stops a comparison as soon as
/// D must exceed lambda (k_S + k_S'). Optionally (default) only mutual best partners are kept.
/// Parallel over the patches, deterministic.
#include <string>
#include <vector>

#include "gasp/association/edit_distance.h"
#include "gasp/association/feature_match.h"
#include "gasp/association/feature_sets.h"
#include "gasp/association/patch_geometry.h"

namespace gasp {

struct AssociationParams {
  /// Neighbourhoods, features and ordering. The neighbourhood default here is the k = 30
  /// nearest patches (the paper used full views; docs/association.md has the measurements).
  FeatureSetParams feature_sets = defaultFeatureSets();
  MatchParams match;   ///< r_dev = 0.04 m, theta_dev = 10 deg (paper)
  EditCosts costs;     ///< insert = delete = 1, replace disabled, transposition 0 (paper)
  int candidates = 75;   ///< C, KD-tree candidates per patch (paper: 75)
  double lambda = 0.5;   ///< gating on D_hat, in [0, 1] (paper: 0.65 - 0.8 before RANSAC)
  /// Keep (a, b) only when a is also b's best partner in A (B -> A search, twice the matching
  /// time). Not in the paper; on fr1_xyz 0 -> 10 it lifts precision from 0.26 to 0.63.
  bool mutual_check = true;

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
  std::size_t comparisons = 0;        ///< edit distances computed (A patch x candidate)
  std::size_t cut_early = 0;          ///< of those, stopped by early termination
  std::size_t comparisons_full = 0;   ///< comparisons a search without KD-tree would make
  std::size_t gated_out = 0;          ///< best candidate found but D_hat > lambda (both directions)
  std::size_t not_mutual = 0;         ///< A -> B partners dropped by the mutual check
  double features_ms = 0, tree_ms = 0, matching_ms = 0;
};

struct AssociationResult {
  std::vector<PatchAssociation> associations;  ///< sorted by patch of A
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
