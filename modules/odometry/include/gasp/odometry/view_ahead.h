#pragma once
/// \file view_ahead.h Segmenting the next frame while the odometry registers the current one.
///
/// A frame's two stages are its segmentation (makeDepthView()) and its registration. The
/// segmentation needs nothing of the odometry's state unless the frame is deskewed (the deskew
/// needs the velocity its predecessor's registration measures), so with
/// rolling_shutter_readout_s = 0 the next frame can be segmented on a second thread while the
/// current one is registered. The result is the same view addFrame() would make: the poses are
/// identical, only sooner.
#include <opencv2/core.hpp>

#include <future>
#include <optional>

#include "gasp/core/camera_intrinsics.h"
#include "gasp/odometry/odometry_params.h"
#include "gasp/pipeline/depth_view.h"

namespace gasp {

/// A frame's view made ahead of its addFrame(), with the time it took.
struct SegmentedDepth {
  DepthView view;
  double ms = 0.0;  ///< makeDepthView()'s time on its own thread
};

/// One segmentation at a time on a background thread (std::async).
class ViewAhead {
 public:
  /// Segments with `params.pair.segment`; does nothing when `params` deskew or `enabled` is
  /// false (then every take() is empty and addFrame() segments as without it).
  explicit ViewAhead(const OdometryParams& params, bool enabled = true);
  ~ViewAhead();
  ViewAhead(const ViewAhead&) = delete;
  ViewAhead& operator=(const ViewAhead&) = delete;

  /// Starts segmenting `depth_m` (shared, not copied: the caller leaves it unchanged until take())
  /// after waiting for the one started before, if it was not taken.
  void start(const cv::Mat& depth_m, const CameraIntrinsics& intrinsics);
  /// The view of the depth started last, waiting for it; empty when none was started, when the
  /// odometry deskews, or when the segmentation failed (addFrame() then segments the frame itself
  /// and reports the error as it would without this).
  std::optional<SegmentedDepth> take();

 private:
  SuperpixelParams superpixels_;
  bool enabled_ = false;
  std::future<SegmentedDepth> pending_;
};

}  // namespace gasp
