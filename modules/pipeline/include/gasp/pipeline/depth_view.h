#pragma once
/// \file depth_view.h One depth view ready for association: the depth image, its projection (a
/// pinhole camera's intrinsics or a range image's grid) and its depth-superpixel decomposition
/// (paper III-A).
#include <opencv2/core.hpp>

#include <memory>
#include <utility>

#include "gasp/core/camera_intrinsics.h"
#include "gasp/core/view_projection.h"
#include "gasp/superpixels/superpixel_params.h"
#include "gasp/superpixels/surface_patch.h"

namespace gasp {

class SweepReturns;  // returns_stage.h

struct DepthView {
  /// CV_32FC1 [m], 0 or NaN = no data: a pinhole camera's depth z (undistorted, see
  /// makeDepthView) or a range image's range along each cell's ray (makeRangeView).
  cv::Mat depth_m;
  ViewProjection projection;  ///< a pinhole without distortion coefficients, or a spherical grid
  SuperpixelSegmentation segmentation;
  /// The parameters `segmentation` was made with (makeDepthView sets them). The finer-scale retry
  /// of registerViews() segments the view again with these at a smaller target area.
  SuperpixelParams superpixels;
  /// A LiDAR view's sweep (makeRangeView): its returns with their normals, on which the pair's
  /// last stage refines the pose (returns_stage.h); null for a camera's view. Shared, immutable.
  std::shared_ptr<const SweepReturns> returns;
};

/// Segments `depth_m` (see segmentDepthSuperpixels(); throws gasp::Error for a wrong image type
/// or size). A view without valid depth has no patches; it is not an error here. When the
/// intrinsics carry lens distortion the depth is first resampled to the pinhole camera
/// (undistortion.h), and the view holds that depth and the pinhole intrinsics; TumDataset's images
/// are already resampled, MRPT observations with plumb_bob coefficients are resampled here.
DepthView makeDepthView(const cv::Mat& depth_m, const CameraIntrinsics& intrinsics,
                        const SuperpixelParams& params = {});
/// The same with any projection: a pinhole as above, a spherical grid's image segmented as it is.
DepthView makeDepthView(const cv::Mat& depth_m, const ViewProjection& projection, const SuperpixelParams& params = {});

/// Two views segmented concurrently (one TBB task each; the segmentation of one frame is
/// single-threaded): the front-end's first stage on 2 threads. Same results as two
/// makeDepthView() calls; the first exception is rethrown.
std::pair<DepthView, DepthView> makeDepthViews(const cv::Mat& depth_a, const cv::Mat& depth_b,
                                               const CameraIntrinsics& intrinsics,
                                               const SuperpixelParams& params = {});

}  // namespace gasp
