#pragma once
/// \file plane_hypothesis.h The hypothesis for views whose own geometry leaves directions free
/// (a floor, a table top: certify_stage.h's view check) when association gives none: inside one
/// large plane every patch looks like every other, so RANSAC over patch centroids finds no
/// consensus, yet the plane itself fixes three directions. Each view's dominant plane -- the
/// largest area of patches within kPlaneAngleDeg and kPlaneOffsetM of one patch's plane -- is
/// aligned: the smallest rotation taking the source plane's normal onto the target's, and the
/// translation taking the source plane's centroid onto the target's. The dense rounds then refine
/// the directions the plane observes and leave the others where this puts them; the certificate
/// reports them free (a partial pose). The alignment is made only when it is unique: a view that
/// also holds a parallel plane of at least kParallelAmbiguity times the dominant plane's area (a
/// floor under a table top) could be matched the other way round after a change of viewpoint,
/// and nothing in the planes tells which.
#include <optional>

#include "gasp/core/pose.h"
#include "gasp/superpixels/surface_patch.h"

namespace gasp {

inline constexpr double kPlaneAngleDeg = 10.0;  ///< a patch's normal within this of the plane's
inline constexpr double kPlaneOffsetM = 0.05;   ///< its centroid within this of the plane [m]
inline constexpr double kParallelAmbiguity = 0.5;  ///< a parallel plane this large makes it ambiguous

/// A plane: unit normal (towards the camera, as the patches') and the area-weighted centroid of
/// its patches, in the view's camera frame.
struct DominantPlane {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  double area_m2 = 0.0;  ///< of its patches
  double share = 0.0;    ///< of the view's patch area
  /// Area of the largest other plane parallel to it (normal within kPlaneAngleDeg, beyond
  /// kPlaneOffsetM) [m^2].
  double parallel_area_m2 = 0.0;
  bool ambiguous() const { return parallel_area_m2 >= kParallelAmbiguity * area_m2; }
};

/// The view's dominant plane; nullopt without a usable patch.
std::optional<DominantPlane> dominantPlane(const SuperpixelSegmentation& view);

/// T_target_source aligning the source view's dominant plane with the target view's (the file's
/// comment); nullopt when either plane is ambiguous.
std::optional<Isometry3> planeHypothesis(const DominantPlane& source, const DominantPlane& target);

/// The alignment itself.
Isometry3 alignPlanes(const DominantPlane& source, const DominantPlane& target);

}  // namespace gasp
