#pragma once
/// \file normals.h Surface normals and a crease measure for an organised cloud (integral images,
/// depth-adaptive windows that stop at depth discontinuities).
#include <opencv2/core.hpp>

#include "gasp/core/camera_intrinsics.h"
#include "gasp/core/point_cloud.h"
#include "gasp/superpixels/superpixel_params.h"

namespace gasp {

struct SurfaceNormals {
  cv::Mat normals;  ///< CV_32FC3 unit normals facing the camera; (0,0,0) where none
  cv::Mat crease;   ///< CV_32F angle [rad] between the normals across the pixel's window; NaN where none
  cv::Mat radius;   ///< CV_32S window half-size used [px]; 0 where no normal
  bool hasNormal(int u, int v) const { return radius.at<int>(v, u) > 0; }
};

/// True when two depths [m] of neighbouring pixels belong to one surface (params' discontinuity rule).
inline bool depthConnected(float z1, float z2, const SuperpixelParams& p) {
  const float z = z1 < z2 ? z1 : z2;
  const float d = z1 > z2 ? z1 - z2 : z2 - z1;
  return d <= static_cast<float>(p.discontinuity_abs_m + p.discontinuity_rel * z * z);
}

/// Normals by the difference of mean points of the half-windows right/left and below/above the
/// pixel (an average 3D gradient; Holzer et al. 2012 use the same integral-image idea).
SurfaceNormals estimateNormals(const OrganizedPointCloud& cloud, const CameraIntrinsics& intrinsics,
                               const SuperpixelParams& params);

}  // namespace gasp
