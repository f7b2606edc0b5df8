#pragma once
/// \file frame_cache.h gasp-pairs: each frame's views and descriptions, made once and kept while
/// later pairs may use them (pairs are visited by start frame, so frames before the current
/// start are dropped).
#include <opencv2/core.hpp>

#include <cstddef>
#include <functional>
#include <map>
#include <utility>

#include "gasp/core/tum_dataset.h"
#include "gasp/pipeline/depth_view.h"
#ifdef GASP_HAVE_BASELINES
#include "gasp/baselines/baseline_registration.h"
#endif

namespace gasp::pairs {

class FrameCache {
 public:
  /// Applied to each depth image (metres) before GASP's segmentation; none: the image as loaded.
  using DepthFilter = std::function<cv::Mat(std::size_t, const cv::Mat&)>;
  explicit FrameCache(const TumDataset& ds, DepthFilter filter = {}) : ds_(ds), filter_(std::move(filter)) {}

  struct GaspView {
    DepthView view;
    double ms = 0;  ///< segmentation time (not the loading or the filter)
  };
  /// Frame i segmented; turned clockwise by `turn_deg` first (camera_roll.h), a view of its own.
  const GaspView& gaspView(std::size_t i, const SuperpixelParams& params, int turn_deg = 0);

#ifdef GASP_HAVE_BASELINES
  /// Frame i as the baselines get it (undistorted where the lens is; never deskewed).
  const baselines::RgbdImage& rgbd(std::size_t i);
  /// Frame i's keypoints and descriptors of baseline `m`.
  const baselines::DescribedKeypoints& described(std::size_t i, baselines::BaselineMethod m,
                                                 const baselines::BaselineParams& params);
#endif

  /// Forgets every frame before `first`.
  void dropBefore(std::size_t first);

 private:
  const TumDataset& ds_;
  DepthFilter filter_;
  std::map<std::pair<std::size_t, int>, GaspView> gasp_;  ///< (frame, turn) -> view
#ifdef GASP_HAVE_BASELINES
  std::map<std::size_t, baselines::RgbdImage> rgbd_;
  std::map<std::pair<std::size_t, int>, baselines::DescribedKeypoints> described_;
#endif
};

}  // namespace gasp::pairs
