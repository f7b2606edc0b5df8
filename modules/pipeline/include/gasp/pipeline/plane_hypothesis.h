#pragma once
/// \file plane_hypothesis.h The hypothesis for views whose own geometry leaves directions free
/// (a floor, a table top: certify_stage.h's view check) when association gives none: inside one
/// large plane every patch looks like every other, so RANSAC over patch centroids finds no
/// consensus, yet the plane itself fixes three directions. Each view's dominant plane -- the
/// largest area of patches within kPlaneAngleDeg and kPlaneOffsetM of one patch's plane -- is
/// aligned: the smallest rotation taking the source plane's normal onto the target's, and the
/// translation taking the source plane's centroid onto the target's. The dense rounds then refine
/// the directions the plane observes and leave the others where this puts them; the certificate
/// reports them free (a partial pose).
#include <optional>

#include "gasp/core/pose.h"
#include "gasp/superpixels/surface_patch.h"

namespace gasp {

inline constexpr double kPlaneAngleDeg = 10.0;  ///< a patch's normal within this of the plane's
inline constexpr double kPlaneOffsetM = 0.05;   ///< its centroid within this of the plane [m]

/// A plane: unit normal (towards the camera, as the patches') and the area-weighted centroid of
/// its patches, in the view's camera frame.
struct DominantPlane {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  double area_m2 = 0.0;  ///< of its patches
  double share = 0.0;    ///< of the view's patch area
};

/// The view's dominant plane; nullopt without a usable patch.
std::optional<DominantPlane> dominantPlane(const SuperpixelSegmentation& view);

/// T_target_source aligning the source's dominant plane with the target's (the file's comment).
Isometry3 alignPlanes(const DominantPlane& source, const DominantPlane& target);

}  // namespace gasp
