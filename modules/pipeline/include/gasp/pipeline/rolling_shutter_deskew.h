#pragma once
/// \file rolling_shutter_deskew.h A depth frame deskewed for the sensor's rolling shutter
/// (gasp/core/rolling_shutter.h) with the camera velocity GASP measures between the frame's
/// neighbours: a sequence gives it for free (odometry registers consecutive frames anyway), a
/// lone pair of frames does not have it.
///
/// Why: a Kinect's depth images carry a rolling shutter of about 30 ms, which a moving camera
/// turns into a distorted view; deskewing with the velocity from frames i-1 and i+1 lowers the
/// pair errors about as much as the motion capture's velocity would (docs/pipeline.md,
/// "Rolling shutter").
#include <opencv2/core.hpp>

#include <cstddef>
#include <string>
#include <utility>

#include "gasp/core/camera_intrinsics.h"
#include "gasp/core/rolling_shutter.h"
#include "gasp/core/tum_dataset.h"
#include "gasp/pipeline/depth_view.h"
#include "gasp/pipeline/pair_registration.h"

namespace gasp {

struct DeskewParams {
  /// Time from the first row's exposure to the last's [s]; negative when the sensor reads
  /// bottom-up; 0 = no deskew. TUM's Kinect (fr1, fr3): 0.03, measured (docs/pipeline.md).
  double readout_s = 0.0;
  /// A measured velocity above either limit (or not finite) is not trusted: the frame is left
  /// as it is. A hand-held or robot camera seldom exceeds 1 m/s or 1.5 rad/s; a wrong
  /// registration can give anything.
  double max_speed_mps = 3.0;   ///< [m/s], > 0
  double max_rate_radps = 3.0;  ///< [rad/s], > 0
};

/// Throws gasp::Error for a non-finite readout or a limit that is not positive.
void validate(const DeskewParams& params);

struct DeskewOutcome {
  cv::Mat depth_m;              ///< the deskewed depth (pinhole), or the input's pinhole depth when not deskewed
  CameraIntrinsics intrinsics;  ///< pinhole intrinsics of depth_m
  bool deskewed = false;        ///< false: depth_m is the input (resampled to the pinhole camera)
  CameraTwist twist;            ///< the velocity used (deskewed only)
  std::string reason;           ///< why not deskewed (empty when deskewed)
};

/// The camera velocity over [t_before, t_after] from registerViews(after, before, pair), and
/// `depth_m` (the frame between them, with `intrinsics`; lens distortion is resampled first)
/// deskewed with it. No pose between the neighbours, a degenerate one or an implausible
/// velocity: the frame is returned as it is, with the reason. Throws gasp::Error for invalid
/// params, dt_s not positive, or a depth image deskewDepth() refuses.
DeskewOutcome deskewWithNeighbours(const cv::Mat& depth_m, const CameraIntrinsics& intrinsics,
                                   const DepthView& before, const DepthView& after, double dt_s,
                                   const DeskewParams& params, const PairParams& pair = {});

/// The frames whose registration measures frame i's velocity in a sequence of n frames: i - 1 and
/// i + 1, or i itself at either end (the same frame twice when n is 1).
std::pair<std::size_t, std::size_t> neighbourFrames(std::size_t i, std::size_t n);

/// Frame i of a TUM folder (`depth_m`, as ds.loadDepth(i) gives it) deskewed with the velocity
/// between its neighbourFrames(): both segmented with pair.segment, then
/// deskewWithNeighbours(). No readout time or no neighbouring frame: not deskewed, with the
/// reason, and the neighbours are not loaded.
DeskewOutcome deskewTumFrame(const TumDataset& ds, std::size_t i, const cv::Mat& depth_m,
                             const DeskewParams& params, const PairParams& pair = {});

}  // namespace gasp
