#include "frame_cache.h"

#include <chrono>

#include "gasp/core/camera_roll.h"
#include "gasp/core/stopwatch.h"

namespace gasp::pairs {

const FrameCache::GaspView& FrameCache::gaspView(std::size_t i, const SuperpixelParams& params, int turn_deg) {
  auto it = gasp_.find({i, turn_deg});
  if (it != gasp_.end()) return it->second;
  cv::Mat depth = filter_ ? filter_(i, ds_.loadDepth(i)) : ds_.loadDepth(i);
  CameraIntrinsics K = ds_.intrinsics();
  if (turn_deg != 0) {
    depth = turnImage(depth, turn_deg);
    K = turnIntrinsics(K, turn_deg);
  }
  const auto t0 = std::chrono::steady_clock::now();
  GaspView v{makeDepthView(depth, K, params), 0.0};
  v.ms = msSince(t0);
  return gasp_.emplace(std::make_pair(i, turn_deg), std::move(v)).first->second;
}

#ifdef GASP_HAVE_BASELINES
const baselines::RgbdImage& FrameCache::rgbd(std::size_t i) {
  auto it = rgbd_.find(i);
  if (it != rgbd_.end()) return it->second;
  return rgbd_.emplace(i, baselines::RgbdImage{ds_.loadDepth(i), ds_.loadRgb(i), ds_.intrinsics()}).first->second;
}

const baselines::DescribedKeypoints& FrameCache::described(std::size_t i, baselines::BaselineMethod m,
                                                           const baselines::BaselineParams& params) {
  const auto key = std::make_pair(i, static_cast<int>(m));
  auto it = described_.find(key);
  if (it != described_.end()) return it->second;
  const auto& view = rgbd(i);
  baselines::DescribedKeypoints k;
  switch (m) {
    case baselines::BaselineMethod::kFpfh:
      k = describePointFeatures(view, baselines::PointFeatureType::kFpfh, params.point);
      break;
    case baselines::BaselineMethod::kShot:
      k = describePointFeatures(view, baselines::PointFeatureType::kShot, params.point);
      break;
    case baselines::BaselineMethod::kColourShot:
      k = describePointFeatures(view, baselines::PointFeatureType::kColourShot, params.point);
      break;
    case baselines::BaselineMethod::kSift: k = describeSift(view, params.sift); break;
    case baselines::BaselineMethod::kDenseSift: k = describeDenseSift(view, params.dense_sift); break;
  }
  return described_.emplace(key, std::move(k)).first->second;
}
#endif

void FrameCache::dropBefore(std::size_t first) {
  gasp_.erase(gasp_.begin(), gasp_.lower_bound(std::make_pair(first, -1)));
#ifdef GASP_HAVE_BASELINES
  rgbd_.erase(rgbd_.begin(), rgbd_.lower_bound(first));
  described_.erase(described_.begin(), described_.lower_bound(std::make_pair(first, -1)));
#endif
}

}  // namespace gasp::pairs
