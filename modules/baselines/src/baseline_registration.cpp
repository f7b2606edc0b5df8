#include "gasp/baselines/baseline_registration.h"

#include <chrono>
#include <tuple>
#include <utility>

#include "gasp/core/error.h"
#include "gasp/core/stopwatch.h"

namespace gasp::baselines {

namespace {

DescribedKeypoints describe(const RgbdImage& view, BaselineMethod method, const BaselineParams& params) {
  switch (method) {
    case BaselineMethod::kFpfh: return describePointFeatures(view, PointFeatureType::kFpfh, params.point);
    case BaselineMethod::kShot: return describePointFeatures(view, PointFeatureType::kShot, params.point);
    case BaselineMethod::kColourShot: return describePointFeatures(view, PointFeatureType::kColourShot, params.point);
    case BaselineMethod::kSift: return describeSift(view, params.sift);
    case BaselineMethod::kDenseSift: return describeDenseSift(view, params.dense_sift);
  }
  throw Error("unknown baseline method");
}

}  // namespace

void validate(const BaselineParams& p) {
  validate(p.point);
  validate(p.sift);
  validate(p.dense_sift);
  validate(p.matching);
  validate(p.pose);
  validate(p.visibility);
}

namespace {

/// Matches, correspondences, RANSAC and the free-space check on the views' depth and projection
/// (the part every baseline shares).
BaselineResult poseFromKeypoints(DescribedKeypoints source_keypoints, DescribedKeypoints target_keypoints,
                                 const DepthView& source, const DepthView& target, const BaselineParams& params) {
  BaselineResult r;
  r.source = std::move(source_keypoints);
  r.target = std::move(target_keypoints);
  r.timings.describe_ms = r.source.describe_ms + r.target.describe_ms;
  auto t0 = std::chrono::steady_clock::now();
  r.matches = matchDescriptors(r.source.descriptors, r.target.descriptors, params.matching);
  r.timings.match_ms = msSince(t0);
  if (r.matches.empty()) {
    r.pose.reason = "no matches (" + std::to_string(r.source.size()) + " and " + std::to_string(r.target.size()) +
                    " keypoints)";
    return r;
  }
  r.correspondences.reserve(r.matches.size());
  for (const auto& m : r.matches) {
    const auto a = static_cast<std::size_t>(m.a), b = static_cast<std::size_t>(m.b);
    r.correspondences.push_back({r.source.points[a], r.source.normals[a], r.target.points[b], r.target.normals[b], 1.0});
  }
  r.pose = estimatePose(r.correspondences, params.pose);
  r.timings.ransac_ms = r.pose.ransac_ms + r.pose.refine_ms;
  if (!r.pose.success) return r;
  t0 = std::chrono::steady_clock::now();
  r.visibility = checkVisibility(source, target, r.pose.T_target_source, params.visibility);
  r.timings.check_ms = msSince(t0);
  if (!r.visibility.passed) {
    r.pose.success = false;
    r.pose.reason = r.visibility.reason;
  }
  return r;
}

}  // namespace

BaselineResult registerDescribed(const RgbdImage& source, const RgbdImage& target, DescribedKeypoints source_keypoints,
                                 DescribedKeypoints target_keypoints, const BaselineParams& params) {
  validate(params);
  // The same free-space check as GASP's: it reads only depth and intrinsics.
  DepthView s, t;
  s.depth_m = source.depth_m;
  s.projection = source.intrinsics;
  t.depth_m = target.depth_m;
  t.projection = target.intrinsics;
  return poseFromKeypoints(std::move(source_keypoints), std::move(target_keypoints), s, t, params);
}

BaselineResult registerWithBaseline(const RgbdImage& source, const RgbdImage& target, BaselineMethod method,
                                    const BaselineParams& params) {
  validate(params);
  validate(source);
  validate(target);
  DescribedKeypoints ks = describe(source, method, params);
  DescribedKeypoints kt = describe(target, method, params);
  return registerDescribed(source, target, std::move(ks), std::move(kt), params);
}

BaselineParams lidarBaselineParams(const LidarParams& lidar) {
  const PairParams pair = lidarPairParams(lidar);
  BaselineParams p;
  p.point.surface.voxel_m = 0.1;
  p.point.surface.normal_radius_m = 0.3;
  p.point.surface.max_depth_m = 100.0;
  p.point.keypoint_voxel_m = 0.3;
  p.point.fpfh_radius_m = 0.6;
  p.point.shot_radius_m = 0.8;
  p.pose = pair.hypothesise.pose;
  p.pose.refine = false;
  p.visibility = pair.certify.visibility;
  return p;
}

BaselineResult registerSweepsWithBaseline(const RangeScan& source, const RangeScan& target, BaselineMethod method,
                                          const BaselineParams& params) {
  validate(params);
  if (method != BaselineMethod::kFpfh && method != BaselineMethod::kShot)
    throw Error("a LiDAR sweep has no image: only the point-feature baselines (FPFH, SHOT) apply");
  validateLayout(source, "baseline: the source sweep");
  validateLayout(target, "baseline: the target sweep");
  const PointFeatureType type = method == BaselineMethod::kFpfh ? PointFeatureType::kFpfh : PointFeatureType::kShot;
  const auto returns = [](const RangeScan& scan) {
    std::vector<Eigen::Vector3f> points;
    for (const Eigen::Vector3d& p : scan.points()) points.push_back(p.cast<float>());
    return points;
  };
  // GASP's free-space check on the sweeps binned as GASP bins them (depth and projection only).
  DepthView s, t;
  std::tie(s.depth_m, s.projection) = binRangeScan(source, lidarSuperpixelParams());
  std::tie(t.depth_m, t.projection) = binRangeScan(target, lidarSuperpixelParams());
  return poseFromKeypoints(describePointFeatures(returns(source), type, params.point),
                           describePointFeatures(returns(target), type, params.point), s, t, params);
}

}  // namespace gasp::baselines
