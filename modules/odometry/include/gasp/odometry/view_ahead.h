#pragma once
/// \file view_ahead.h Segmenting the next frames while the odometry registers the current one.
///
/// A frame's two stages are its segmentation (makeDepthView()) and its registration. The
/// segmentation needs nothing of the odometry's state unless the frame is deskewed (the deskew
/// needs the velocity its predecessor's registration measures), so with
/// rolling_shutter_readout_s = 0 (a camera's frames) or deskew_sweeps off (a LiDAR's sweeps) the
/// next frames can be segmented on threads of their own while the current one is registered. The result is the same view addFrame() would make: the poses are
/// identical, only sooner.
#include <opencv2/core.hpp>

#include <deque>
#include <future>
#include <optional>

#include "gasp/core/camera_intrinsics.h"
#include "gasp/core/range_scan.h"
#include "gasp/odometry/odometry_params.h"
#include "gasp/pipeline/depth_view.h"

namespace gasp {

/// A frame's view made ahead of its addFrame(), with the time it took.
struct SegmentedDepth {
  DepthView view;
  double ms = 0.0;  ///< makeDepthView()'s time on its own thread
};

/// Segmentations on background threads (std::async), taken in the order they were started.
class ViewAhead {
 public:
  /// Segments with `params.pair.segment`; does nothing when `enabled` is false or `params` deskew
  /// depth images (rolling_shutter_readout_s): then every take() is empty and addFrame() segments
  /// as without it. With `params.deskew_sweeps` a sweep whose columns carry their times
  /// (sweepTimed()) is not segmented ahead either: its take() is empty.
  explicit ViewAhead(const OdometryParams& params, bool enabled = true);
  ~ViewAhead();
  ViewAhead(const ViewAhead&) = delete;
  ViewAhead& operator=(const ViewAhead&) = delete;

  /// Starts segmenting `depth_m` (shared, not copied: the caller leaves it unchanged until its
  /// take()) on a thread of its own; the caller bounds how many run at once (frames_ahead.h).
  void start(const cv::Mat& depth_m, const CameraIntrinsics& intrinsics);
  /// The same for a LiDAR sweep (makeRangeView() with params.pair.segment and params.pair.returns;
  /// the scan is copied, its range image shared).
  void start(const RangeScan& sweep);
  /// The view of the oldest start() not yet taken, waiting for it; empty when none is pending,
  /// when the odometry deskews, when that depth was not segmented (addFrame() would refuse it) or
  /// when the segmentation failed (addFrame() then segments the frame itself and reports the
  /// error as it would without this).
  std::optional<SegmentedDepth> take();

 private:
  SuperpixelParams superpixels_;
  ReturnsRefineParams returns_;
  bool enabled_ = false;
  bool deskew_sweeps_ = false;  ///< timed sweeps are not segmented ahead
  std::deque<std::future<SegmentedDepth>> pending_;  ///< oldest first; invalid: not segmented
};

}  // namespace gasp
