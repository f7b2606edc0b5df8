#pragma once
/// \file symmetric_turns.h The alternatives of the certificate's symmetry test (certify_stage.h,
/// CertifyParams::symmetry_test): a claimed pose turned by a quarter, a half and three quarters
/// about each principal axis of the target's patch normals.
///
/// Why: a scene shaped like a box (a near-square room, a street between facades) maps onto itself
/// under such a turn, and association can then prefer the turned pose; RANSAC offers no distinct
/// alternative, since its hypotheses all come from the same look-alike associations. The true
/// pose is then among these turns of the claimed one, and the likelihood comparison
/// (compareAlternative()) tells which explains the views better.
#include <Eigen/Core>

#include <vector>

#include "gasp/core/pose.h"
#include "gasp/pipeline/depth_view.h"

namespace gasp {

struct SymmetricTurn {
  Isometry3 T_target_source = Isometry3::Identity();  ///< the turned pose, its translation voted
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();     ///< the target's principal axis (target frame)
  int degrees = 90;                                    ///< 90, 180 or 270
};

/// The claimed pose T_target_source turned about each principal axis of the target's patch normals
/// (the eigenvectors of the area-weighted sum of n n^T) through the mapped source patches'
/// area-weighted centroid; each turn's translation then voted along each axis: the pairs of a
/// source patch (turned) and a target patch both facing along it within 10 deg give the offset of
/// their planes along it, counted in 5 cm bins, and the fullest bin's mean is taken (an axis
/// without such pairs keeps the turn's). Nine turns; none for views without patches.
std::vector<SymmetricTurn> symmetricTurns(const DepthView& source, const DepthView& target,
                                          const Isometry3& T_target_source);

}  // namespace gasp
