#pragma once
/// \file rgb_check.h gasp-pairs --rgb-rotation-check: a depth-free check of a pair. The rotation
/// between the two colour images from their pixels alone (SIFT, essential matrix;
/// epipolar_rotation.h), and the reference's short motions between each frame's depth and rgb
/// stamps, so that poses between the depth frames can be compared with it.
#include <Eigen/Core>

#include <cstddef>
#include <optional>
#include <string>

#include "gasp/core/pose.h"
#include "pair_reference.h"
#ifdef GASP_HAVE_BASELINES
#include "frame_cache.h"
#include "gasp/baselines/epipolar_rotation.h"
#endif

namespace gasp::pairs {

struct RgbCheck {
  bool ran = false;  ///< both frames have rgb
  std::size_t inliers = 0;
  double parallax_px = 0.0;
  std::optional<Eigen::Matrix3d> R_rgb;             ///< R_target_source from the images
  std::optional<Isometry3> T_ref;                   ///< the reference between the rgb stamps
  std::optional<Isometry3> T_di_ri, T_rj_dj;        ///< rgb i -> depth i, depth j -> rgb j
};

#ifdef GASP_HAVE_BASELINES
/// The check of pair (i -> j); not run (`ran` false) unless both frames have rgb. `rgb_camera`:
/// the colour camera of the (undistorted) rgb images.
RgbCheck checkRgbRotation(const TumDataset& ds, FrameCache& cache, const PairReference& reference, std::size_t i,
                          std::size_t j, const CameraIntrinsics& rgb_camera, const baselines::EpipolarParams& params);
#endif

/// The angle [deg] between the images' rotation and a pose between the rgb stamps, as text; ""
/// when either is missing.
std::string rgbAngleText(const RgbCheck& c, const std::optional<Isometry3>& T_rgb);

/// A pose between the depth stamps carried to the rgb stamps by the reference's short motions.
std::optional<Isometry3> toRgbStamps(const RgbCheck& c, const std::optional<Isometry3>& T_dj_di);

}  // namespace gasp::pairs
