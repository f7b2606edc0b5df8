#pragma once
/// \file guided_association.h Associations under a pose hypothesis (guided matching, Hartley and
/// Zisserman 2004, 4.8): patch a of view A and patch b of view B are associated when b's centroid
/// lies within `max_distance_m` of a's centroid mapped by T_b_a, their normals agree within
/// `max_normal_angle_deg`, AND their feature sets agree: D_hat(Q_a, Q_b) <= lambda. Each patch of A
/// keeps its least-D_hat partner (ties: nearer centroid, then lower index); a patch of B chosen
/// by several keeps the least D_hat (same ties), so the result is one-to-one.
///
/// The pose only says where to look; the edit distance still has to accept the pair, so a wrong
/// pose gathers few associations (its support) and a right one gathers the repeatable patches of
/// the overlap that the free search ranked below a look-alike. The pipeline uses it to verify
/// pose hypotheses and to give the refinement every associated patch (pair_registration.h).
#include <vector>

#include "gasp/association/edit_distance.h"
#include "gasp/association/feature_match.h"
#include "gasp/association/invariant_feature.h"
#include "gasp/association/patch_geometry.h"
#include "gasp/association/view_association.h"
#include "gasp/core/pose.h"

namespace gasp {

struct GuidedAssociationParams {
  double max_distance_m = 0.035;       ///< gate on |T_b_a c_a - c_b| [m] (> 0)
  double max_normal_angle_deg = 20.0;  ///< gate on angle(R_b_a n_a, n_b) [deg], in (0, 180]
  double lambda = 0.8;                 ///< gate on D_hat, in [0, 1]
};

/// Throws gasp::Error naming the first invalid parameter.
void validate(const GuidedAssociationParams& params);

/// qa, qb: the feature sets of every patch (computeFeatureSets() with the same parameters for
/// both views; match tolerances and costs from `association`). Patches without a feature set or
/// with non-finite geometry take no part. Sorted by patch of A; distance = D_hat.
std::vector<PatchAssociation> guidedAssociations(const std::vector<PatchGeometry>& a,
                                                 const std::vector<PatchGeometry>& b,
                                                 const std::vector<std::vector<Feature>>& qa,
                                                 const std::vector<std::vector<Feature>>& qb,
                                                 const Isometry3& T_b_a, const AssociationParams& association,
                                                 const GuidedAssociationParams& params = {});

}  // namespace gasp
