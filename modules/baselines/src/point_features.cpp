#include "gasp/baselines/point_features.h"

#include <pcl/features/fpfh_omp.h>
#include <pcl/features/shot_omp.h>
#include <pcl/filters/uniform_sampling.h>

#include <chrono>
#include <cmath>

#include "gasp/core/error.h"
#include "gasp/core/stopwatch.h"
#include "surface_cloud.h"

namespace gasp::baselines {

namespace {

/// Keypoints as indices into the surface cloud: the voxel representatives of UniformSampling
/// (actual surface points), found back by exact nearest-neighbour look-up.
pcl::IndicesPtr sampleKeypoints(const SurfaceCloud& s, const PointFeatureParams& params) {
  pcl::IndicesPtr keep(new pcl::Indices);
  const std::size_t want = static_cast<std::size_t>(params.min_keypoints);
  if (s.points->size() <= want) {
    for (std::size_t i = 0; i < s.points->size(); ++i) keep->push_back(static_cast<int>(i));
  } else {
    pcl::PointCloud<SurfacePoint> sampled;
    for (double r = params.keypoint_voxel_m;; r *= 0.8) {
      pcl::UniformSampling<SurfacePoint> us;
      us.setInputCloud(s.points);
      us.setRadiusSearch(r);
      us.filter(sampled);
      if (sampled.size() >= want || r < params.surface.voxel_m) break;
    }
    pcl::Indices idx;
    std::vector<float> d2;
    for (const auto& q : sampled)
      if (s.tree->nearestKSearch(q, 1, idx, d2) == 1) keep->push_back(idx[0]);
  }
  // Keep only keypoints with a normal (descriptors need it).
  pcl::IndicesPtr out(new pcl::Indices);
  for (int i : *keep) {
    const auto& n = (*s.normals)[static_cast<std::size_t>(i)];
    if (std::isfinite(n.normal_x) && std::isfinite(n.normal_y) && std::isfinite(n.normal_z)) out->push_back(i);
  }
  return out;
}

template <typename Descriptor, std::size_t N>
void collect(const SurfaceCloud& s, const pcl::Indices& keypoints, const pcl::PointCloud<Descriptor>& desc,
             const float (Descriptor::*field)[N], const CameraIntrinsics* K, DescribedKeypoints& out) {
  std::vector<int> rows;
  for (std::size_t k = 0; k < keypoints.size(); ++k) {
    const auto& h = desc[k].*field;
    bool finite = true, nonzero = false;
    for (std::size_t j = 0; j < N; ++j) {
      finite = finite && std::isfinite(h[j]);
      nonzero = nonzero || h[j] != 0.0f;
    }
    if (finite && nonzero) rows.push_back(static_cast<int>(k));
  }
  out.descriptors.create(static_cast<int>(rows.size()), static_cast<int>(N), CV_32F);
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const auto k = static_cast<std::size_t>(rows[r]);
    const auto& h = desc[k].*field;
    float* dst = out.descriptors.ptr<float>(static_cast<int>(r));
    for (std::size_t j = 0; j < N; ++j) dst[j] = h[j];
    const auto i = static_cast<std::size_t>(keypoints[k]);
    const auto& p = (*s.points)[i];
    const auto& n = (*s.normals)[i];
    const Eigen::Vector3d pd(p.x, p.y, p.z);
    out.points.push_back(pd);
    out.normals.push_back(Eigen::Vector3d(n.normal_x, n.normal_y, n.normal_z).normalized());
    double u = -1, v = -1;  // no image: (-1, -1)
    if (K) K->project(pd, u, v);
    out.pixels.emplace_back(static_cast<float>(u), static_cast<float>(v));
  }
}

/// Runs a PCL feature estimator on the keypoints of the surface cloud and collects the result.
template <typename Estimator, typename Descriptor, std::size_t N>
void describe(Estimator& est, const SurfaceCloud& s, const pcl::IndicesPtr& keypoints, double radius_m,
              const float (Descriptor::*field)[N], const CameraIntrinsics* K, DescribedKeypoints& out) {
  est.setInputCloud(s.points);
  est.setIndices(keypoints);
  est.setInputNormals(s.normals);
  est.setSearchMethod(s.tree);
  est.setRadiusSearch(radius_m);
  pcl::PointCloud<Descriptor> desc;
  est.compute(desc);
  collect(s, *keypoints, desc, field, K, out);
}

}  // namespace

void validate(const PointFeatureParams& p) {
  validate(p.surface);
  if (p.min_keypoints < 1) throw Error("PointFeatureParams: min_keypoints must be >= 1");
  if (!(p.keypoint_voxel_m >= p.surface.voxel_m)) throw Error("PointFeatureParams: keypoint_voxel_m must be >= surface.voxel_m");
  if (!(p.fpfh_radius_m > p.surface.normal_radius_m))
    throw Error("PointFeatureParams: fpfh_radius_m must exceed surface.normal_radius_m");
  if (!(p.shot_radius_m > p.surface.voxel_m)) throw Error("PointFeatureParams: shot_radius_m must exceed surface.voxel_m");
}

namespace {

/// Keypoints and descriptors on a surface cloud; K projects them to pixels (null: none).
DescribedKeypoints describeSurface(const SurfaceCloud& s, PointFeatureType type, const PointFeatureParams& params,
                                   const CameraIntrinsics* K, std::chrono::steady_clock::time_point t0) {
  DescribedKeypoints out;
  out.descriptors.create(0, type == PointFeatureType::kFpfh ? 33 : type == PointFeatureType::kShot ? 352 : 1344, CV_32F);
  if (s.points->size() < 3) return out;
  const pcl::IndicesPtr keypoints = sampleKeypoints(s, params);
  if (keypoints->empty()) return out;
  const auto threads = static_cast<unsigned>(params.surface.threads);
  switch (type) {
    case PointFeatureType::kFpfh: {
      pcl::FPFHEstimationOMP<SurfacePoint, pcl::Normal, pcl::FPFHSignature33> est(threads);
      describe(est, s, keypoints, params.fpfh_radius_m, &pcl::FPFHSignature33::histogram, K, out);
      break;
    }
    case PointFeatureType::kShot: {
      pcl::SHOTEstimationOMP<SurfacePoint, pcl::Normal, pcl::SHOT352> est(threads);
      describe(est, s, keypoints, params.shot_radius_m, &pcl::SHOT352::descriptor, K, out);
      break;
    }
    case PointFeatureType::kColourShot: {
      pcl::SHOTColorEstimationOMP<SurfacePoint, pcl::Normal, pcl::SHOT1344> est(true, true, threads);
      describe(est, s, keypoints, params.shot_radius_m, &pcl::SHOT1344::descriptor, K, out);
      break;
    }
  }
  out.describe_ms = msSince(t0);
  return out;
}

}  // namespace

DescribedKeypoints describePointFeatures(const RgbdImage& view, PointFeatureType type, const PointFeatureParams& params) {
  validate(params);
  if (type == PointFeatureType::kColourShot && view.bgr.empty())
    throw Error("colour SHOT needs the view's colour image (none given)");
  const auto t0 = std::chrono::steady_clock::now();
  return describeSurface(makeSurfaceCloud(view, params.surface), type, params, &view.intrinsics, t0);
}

DescribedKeypoints describePointFeatures(const std::vector<Eigen::Vector3f>& points, PointFeatureType type,
                                         const PointFeatureParams& params) {
  validate(params);
  if (type == PointFeatureType::kColourShot) throw Error("colour SHOT needs colour; points have none");
  const auto t0 = std::chrono::steady_clock::now();
  return describeSurface(makeSurfaceCloud(points, params.surface), type, params, nullptr, t0);
}

}  // namespace gasp::baselines
