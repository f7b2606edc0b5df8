#pragma once
// The slide scan's search (gasp/pipeline/slide_scan.h, docs/pipeline.md "Slide scan"): used by
// the refine stage (refine_stage.h) on a claimed pose whose patch problem was degenerate, and on
// a partial pose along its view's dominant plane.
#include <functional>

#include "gasp/pipeline/depth_view.h"
#include "gasp/pipeline/slide_scan.h"
#include "gasp/pipeline/visibility_check.h"
#include "gasp/registration/registration_result.h"

namespace gasp::detail {

struct SlideScanOutcome {
  SlideScanReport report;
  RegistrationResult pose;  ///< the refined pose from the best offset (when report.moved)
  VisibilityCheck check;    ///< its visibility check (when report.moved)
};

/// `claimed`: the pose the dense rounds gave (it passed the visibility check); `patch_pose`: the
/// patch problem's result, whose unobservable directions, scene centre and radius define the
/// scan. `refine_from(T)` runs the dense refinement from start T; its pose must be full, or with
/// `partial_ok` full or partial. `free_space`: the test the claimed pose faces (certify_stage.h);
/// a moved pose must pass it too.
SlideScanOutcome scanSlide(const DepthView& source, const DepthView& target, const RegistrationResult& patch_pose,
                           const Isometry3& claimed, const std::function<RegistrationResult(const Isometry3&)>& refine_from,
                           const SlideScanParams& params, const FreeSpaceTest& free_space, bool partial_ok = false);

/// The directions a plane leaves free -- the two translations along it and the rotation about its
/// normal through its centroid -- as a RegistrationResult's unobservable directions (with its
/// scene centre and radius), for scanSlide().
RegistrationResult planeSymmetries(const Eigen::Vector3d& normal, const Eigen::Vector3d& centroid, double radius_m);

}  // namespace gasp::detail
