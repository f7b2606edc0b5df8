#pragma once
/// \file baseline_registration.h The relative pose of two views from a feature baseline, with the
/// same pose stage and the same failure definition as GASP's RANSAC-only variant (gasp-pairs
/// --method gasp-norefine):
///   1. keypoints and descriptors of both views (point_features.h, sift_features.h,
///      dense_sift_features.h);
///   2. matches by nearest neighbour, ratio test and mutual check (descriptor_matching.h);
///   3. each match becomes a PatchCorrespondence (keypoint points and normals, weight 1);
///   4. gasp::estimatePose with refine = false: RANSAC over the 3D points with the same
///      parameters as GASP's pipeline (PairParams::defaultPoseParams(): 0.05 m / 20 deg inliers,
///      at least 8), the pose evaluated for degeneracy as GASP's is;
///   5. gasp::checkVisibility on the depth images with GASP's parameters.
/// No estimate (failure) = no consensus, a degenerate estimate, or a failed visibility check.
#include <string>
#include <vector>

#include "gasp/baselines/baseline_method.h"
#include "gasp/baselines/dense_sift_features.h"
#include "gasp/baselines/described_keypoints.h"
#include "gasp/baselines/descriptor_matching.h"
#include "gasp/baselines/point_features.h"
#include "gasp/baselines/rgbd_image.h"
#include "gasp/baselines/sift_features.h"
#include "gasp/core/range_scan.h"
#include "gasp/pipeline/pair_registration.h"
#include "gasp/pipeline/range_view.h"
#include "gasp/pipeline/visibility_check.h"
#include "gasp/registration/register_patches.h"

namespace gasp::baselines {

struct BaselineParams {
  PointFeatureParams point;  ///< FPFH, SHOT, colour SHOT
  SiftParams sift;
  DenseSiftParams dense_sift;
  MatchParams matching;      ///< ratio 0.8, mutual check
  /// GASP's pose parameters with refine = false (RANSAC only, then the evaluation).
  PoseEstimationParams pose = defaultPoseParams();
  VisibilityCheckParams visibility;  ///< GASP's

  static PoseEstimationParams defaultPoseParams() {
    PoseEstimationParams p = HypothesiseParams::defaultPose();
    p.refine = false;
    return p;
  }
};

/// Throws gasp::Error naming the first invalid parameter.
void validate(const BaselineParams& params);

struct BaselineTimings {
  double describe_ms = 0, match_ms = 0, ransac_ms = 0, check_ms = 0;
  double total() const { return describe_ms + match_ms + ransac_ms + check_ms; }
};

struct BaselineResult {
  RegistrationResult pose;  ///< pose.success = an estimate is claimed; pose.reason otherwise
  DescribedKeypoints source, target;
  std::vector<DescriptorMatch> matches;              ///< a = source keypoint, b = target keypoint
  std::vector<PatchCorrespondence> correspondences;  ///< one per match, same order
  VisibilityCheck visibility;                        ///< of the RANSAC pose, when there was one
  BaselineTimings timings;
};

/// Registers `source` to `target` with one baseline: pose.T_target_source maps the source camera
/// frame into the target's. Never throws for data (no keypoints, no matches: pose.success = false
/// with the reason); throws gasp::Error for invalid parameters or views, and for a colour method
/// on a view without colour.
BaselineResult registerWithBaseline(const RgbdImage& source, const RgbdImage& target, BaselineMethod method,
                                    const BaselineParams& params = {});

/// The pose stage alone (steps 2-5 above) on already described views.
BaselineResult registerDescribed(const RgbdImage& source, const RgbdImage& target, DescribedKeypoints source_keypoints,
                                 DescribedKeypoints target_keypoints, const BaselineParams& params = {});

/// The baselines' values for LiDAR sweeps: a 10 cm surface voxel, normals over 30 cm, returns up
/// to 100 m, keypoints from 30 cm voxels, FPFH over 60 cm and SHOT over 80 cm; RANSAC, inliers and
/// the free-space check are GASP's LiDAR values (lidarPairParams(lidar), RANSAC only).
BaselineParams lidarBaselineParams(const LidarParams& lidar = {});

/// One point-feature baseline (FPFH or SHOT) on two LiDAR sweeps, with the stages of
/// registerWithBaseline(): keypoints and descriptors of each sweep's returns, matches, RANSAC,
/// then the free-space check on the sweeps binned as GASP bins them. Never throws for data;
/// throws gasp::Error for invalid parameters, a sweep that is no range image, or another method.
BaselineResult registerSweepsWithBaseline(const RangeScan& source, const RangeScan& target, BaselineMethod method,
                                          const BaselineParams& params = lidarBaselineParams());

}  // namespace gasp::baselines
