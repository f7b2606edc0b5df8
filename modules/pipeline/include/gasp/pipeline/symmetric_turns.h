#pragma once
/// \file symmetric_turns.h The alternatives of the certificate's symmetry test (certify_stage.h,
/// CertifyParams::symmetry_test): a claimed pose turned by a quarter, a half and three quarters
/// about each axis of the target's scene (sceneAxes(): its largest faces' normals).
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
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();     ///< the target scene's axis (target frame)
  int degrees = 90;                                    ///< 90, 180 or 270
};

/// The axes of a box-shaped scene from its patches (columns, a rotation): a box's symmetry axes are
/// its faces' normals, so the first is the largest face's (the patch normal with the most patch
/// area within 20 deg of it either way, their area-weighted mean), the second the largest face's
/// within 20 deg of perpendicular to it, the third their cross product; then refined to the
/// normals within 20 deg of each (orthogonal Procrustes, area-weighted) while two or more axes
/// have such normals. Without a second face, the principal axis of the area-weighted sum of
/// n n^T least aligned with the first stands in; without any face (no patch with a finite normal
/// and a positive area), those principal axes. Why not those principal axes alone: where two
/// faces have about the same area (a near-square room's floor and wall) they are arbitrary within
/// those faces' plane.
Eigen::Matrix3d sceneAxes(const std::vector<SurfacePatch>& patches);

/// The claimed pose T_target_source turned about each of the target's sceneAxes() through the
/// mapped source patches' area-weighted centroid; each turn's translation then voted along each axis: the pairs of a
/// source patch (turned) and a target patch both facing along it within 10 deg give the offset of
/// their planes along it, counted in 5 cm bins, and the fullest bin's mean is taken (an axis
/// without such pairs keeps the turn's). Nine turns; none for views without patches.
std::vector<SymmetricTurn> symmetricTurns(const DepthView& source, const DepthView& target,
                                          const Isometry3& T_target_source);
/// The same about the given axes (the columns of `axes`, target frame).
std::vector<SymmetricTurn> symmetricTurns(const DepthView& source, const DepthView& target,
                                          const Isometry3& T_target_source, const Eigen::Matrix3d& axes);

}  // namespace gasp
