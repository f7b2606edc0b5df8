#pragma once
/// \file normals.h Surface normals and a crease measure for an organised cloud (integral images,
/// depth-adaptive windows that stop at depth discontinuities).
#include <opencv2/core.hpp>

#include "gasp/core/point_cloud.h"
#include "gasp/superpixels/depth_links.h"
#include "gasp/superpixels/superpixel_params.h"

namespace gasp {

struct SurfaceNormals {
  cv::Mat normals;  ///< CV_32FC3 unit normals facing the camera; (0,0,0) where none
  cv::Mat crease;   ///< CV_32F angle [rad] between the normals half a window to either side; NaN where none
  cv::Mat radius;   ///< CV_32S window half-size used [px]; 0 where no normal
  /// CV_32FC3 mean point of the pixel's window (the raw point where there is no normal): the
  /// depth noise averaged out, for clustering.
  cv::Mat smoothed;
  bool hasNormal(int u, int v) const { return radius.at<int>(v, u) > 0; }
};

/// Normals by the difference of mean points of the half-windows right/left and below/above the
/// pixel (an average 3D gradient; Holzer et al. 2012 use the same integral-image idea).
SurfaceNormals estimateNormals(const OrganizedPointCloud& cloud, const DepthLinks& links,
                               const SuperpixelParams& params);

}  // namespace gasp
