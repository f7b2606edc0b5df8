#pragma once
/// \file projective_terms.h Dense point-to-plane terms from the patches' pixels, for the final
/// refinement of a pair's pose: each sampled source pixel that lies in a patch is mapped by the
/// current T_target_source and projected into the target image (projective association, as in
/// KinectFusion); the target pixel's point and its patch's normal give the plane. Terms whose
/// points are further apart than a distance gate, or whose patch normals disagree, are left out.
#include <vector>

#include "gasp/core/pose.h"
#include "gasp/pipeline/depth_view.h"
#include "gasp/registration/correspondence.h"

namespace gasp {

struct ProjectiveTermParams {
  /// Sample every pixel_step-th pixel in u and v (>= 1). 8: about as accurate as denser sampling
  /// at a fraction of the time (docs/pipeline.md).
  int pixel_step = 8;
  double max_distance_m = 0.05;    ///< gate on |T p_source - q_target| [m] (> 0)
  /// Widen the gate by the target pixel's footprint on its surface (depth x half a pixel diagonal
  /// / cos(incidence)): for coarse pixels, a LiDAR's binned cells (lidarPairParams). Off for a
  /// camera, whose dense rounds were measured without.
  bool pixel_footprint = false;
  double max_normal_angle_deg = 20.0;  ///< gate on the angle between the two patch normals [deg]
  /// Samples about this far apart in view angle [deg, in [0, 90]]: the step is the larger of
  /// pixel_step and this angle in the source view's pixels, rounded (samplingStep). 0: pixel_step
  /// alone (a camera's). LiDAR sweeps (LidarParams::dense_sample_spacing_deg): about a camera's
  /// spacing, so views of finer cells are not sampled more densely than the rounds were measured on.
  double sample_spacing_deg = 0.0;
};

/// Throws gasp::Error for a parameter out of range.
void validate(const ProjectiveTermParams& params);

/// The pixel step projectiveTerms() samples a view of `projection` with: max(pixel_step,
/// round(sample_spacing_deg in pixels)), pixels per radian as ViewProjection::pixelsPerRadian().
int samplingStep(const ViewProjection& projection, const ProjectiveTermParams& params);

/// The terms for the current pose. Empty when nothing overlaps.
std::vector<PointToPlane> projectiveTerms(const DepthView& source, const DepthView& target,
                                          const Isometry3& T_target_source, const ProjectiveTermParams& params = {});

/// Patch pairs by the same projective association, for a pose known to within a few cm: each
/// source patch's centroid mapped by T_target_source and projected into the target image pairs
/// with the target patch under it when the two would be a RANSAC inlier at that pose -- the
/// mapped centroid within max_distance_m of that patch's centroid, the normals within
/// max_normal_angle_deg (inlier_criterion.h): the same surface patch cut alike in both views.
/// What RANSAC's inliers are to the dense rounds -- one term per patch, so that small
/// structures count beside large planes -- where no association ran (the tracking path,
/// pair_registration.h). Empty when nothing overlaps.
std::vector<PatchCorrespondence> projectivePatchPairs(const DepthView& source, const DepthView& target,
                                                      const Isometry3& T_target_source,
                                                      const ProjectiveTermParams& params = {});

}  // namespace gasp
