#include "gasp/core/camera_roll.h"

#include <opencv2/core.hpp>

#include <string>

#include "gasp/core/error.h"

namespace gasp {

void requireQuarterTurn(int clockwise_deg) {
  if (clockwise_deg != 0 && clockwise_deg != 90 && clockwise_deg != 180 && clockwise_deg != 270)
    throw Error("image turn: " + std::to_string(clockwise_deg) + " deg is not 0, 90, 180 or 270");
}

cv::Mat turnImage(const cv::Mat& image, int clockwise_deg) {
  requireQuarterTurn(clockwise_deg);
  if (clockwise_deg == 0) return image.clone();
  cv::Mat out;
  cv::rotate(image, out,
             clockwise_deg == 90 ? cv::ROTATE_90_CLOCKWISE
                                 : (clockwise_deg == 180 ? cv::ROTATE_180 : cv::ROTATE_90_COUNTERCLOCKWISE));
  return out;
}

CameraIntrinsics turnIntrinsics(const CameraIntrinsics& K, int clockwise_deg) {
  requireQuarterTurn(clockwise_deg);
  if (clockwise_deg == 0) return K;
  for (const double d : K.distortion)
    if (d != 0.0) throw Error("image turn: the camera has lens distortion; undistort the image first");
  CameraIntrinsics t = K;
  const double W = K.width, H = K.height;
  switch (clockwise_deg) {
    case 90:  // (u, v) -> (H-1-v, u)
      t.width = K.height, t.height = K.width;
      t.fx = K.fy, t.fy = K.fx;
      t.cx = H - 1.0 - K.cy, t.cy = K.cx;
      break;
    case 180:  // (u, v) -> (W-1-u, H-1-v)
      t.cx = W - 1.0 - K.cx, t.cy = H - 1.0 - K.cy;
      break;
    case 270:  // (u, v) -> (v, W-1-u)
      t.width = K.height, t.height = K.width;
      t.fx = K.fy, t.fy = K.fx;
      t.cx = K.cy, t.cy = W - 1.0 - K.cx;
      break;
    default: break;
  }
  return t;
}

Isometry3 turnRotation(int clockwise_deg) {
  requireQuarterTurn(clockwise_deg);
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  switch (clockwise_deg) {
    case 90: R << 0, -1, 0, 1, 0, 0, 0, 0, 1; break;   // (x, y, z) -> (-y, x, z)
    case 180: R << -1, 0, 0, 0, -1, 0, 0, 0, 1; break;  // (x, y, z) -> (-x, -y, z)
    case 270: R << 0, 1, 0, -1, 0, 0, 0, 0, 1; break;   // (x, y, z) -> (y, -x, z)
    default: break;
  }
  Isometry3 T = Isometry3::Identity();
  T.linear() = R;
  return T;
}

}  // namespace gasp
