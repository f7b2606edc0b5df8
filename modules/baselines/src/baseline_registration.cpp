#include "gasp/baselines/baseline_registration.h"

#include <chrono>

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

BaselineResult registerDescribed(const RgbdImage& source, const RgbdImage& target, DescribedKeypoints source_keypoints,
                                 DescribedKeypoints target_keypoints, const BaselineParams& params) {
  validate(params);
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
  // The same free-space check as GASP's: it reads only depth and intrinsics.
  DepthView s, t;
  s.depth_m = source.depth_m;
  s.projection = source.intrinsics;
  t.depth_m = target.depth_m;
  t.projection = target.intrinsics;
  r.visibility = checkVisibility(s, t, r.pose.T_target_source, params.visibility);
  r.timings.check_ms = msSince(t0);
  if (!r.visibility.passed) {
    r.pose.success = false;
    r.pose.reason = r.visibility.reason;
  }
  return r;
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

}  // namespace gasp::baselines
