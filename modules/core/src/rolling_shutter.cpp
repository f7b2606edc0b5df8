#include "gasp/core/rolling_shutter.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "gasp/core/error.h"

namespace gasp {

CameraTwist twistBetween(const Isometry3& T_world_a, const Isometry3& T_world_b, double dt_s) {
  if (!(std::isfinite(dt_s) && dt_s > 0.0)) throw Error("twistBetween: the time step must be positive");
  const Isometry3 T_a_b = T_world_a.inverse() * T_world_b;
  const Eigen::AngleAxisd aa(T_a_b.linear());
  CameraTwist twist;
  twist.w_radps = aa.axis() * aa.angle() / dt_s;
  twist.v_mps = T_a_b.translation() / dt_s;
  return twist;
}

namespace {

/// The pose of the camera at row r relative to the stamp's: exp([w dt]), v dt.
struct RowMotion {
  Eigen::Matrix3d R;
  Eigen::Vector3d t;
};

std::vector<RowMotion> rowMotions(int rows, const CameraTwist& twist, double readout_s) {
  std::vector<RowMotion> motions(static_cast<std::size_t>(rows));
  const double w = twist.w_radps.norm();
  for (int r = 0; r < rows; ++r) {
    const double dt = (rows > 1 ? static_cast<double>(r) / (rows - 1) - 0.5 : 0.0) * readout_s;
    auto& m = motions[static_cast<std::size_t>(r)];
    m.R = w > 0.0 ? Eigen::AngleAxisd(w * dt, twist.w_radps / w).toRotationMatrix()
                  : Eigen::Matrix3d::Identity();
    m.t = twist.v_mps * dt;
  }
  return motions;
}

constexpr double kSurfaceRatio = 0.03;  ///< neighbours within 3 % of depth: one surface
constexpr int kIterations = 8;
constexpr double kConvergedPx = 0.05;

}  // namespace

cv::Mat deskewDepth(const cv::Mat& depth, const CameraIntrinsics& k, const CameraTwist& twist,
                    double readout_s) {
  k.validate();
  if (depth.type() != CV_32FC1) throw Error("deskewDepth: the depth image must be CV_32FC1 (metres)");
  if (depth.cols != k.width || depth.rows != k.height)
    throw Error("deskewDepth: the depth image is " + std::to_string(depth.cols) + "x" +
                std::to_string(depth.rows) + " but the intrinsics are for " + std::to_string(k.width) + "x" +
                std::to_string(k.height));
  if (!std::isfinite(readout_s) || !twist.v_mps.allFinite() || !twist.w_radps.allFinite())
    throw Error("deskewDepth: the readout time and the twist must be finite");
  if (readout_s == 0.0) return depth.clone();

  const auto motions = rowMotions(depth.rows, twist, readout_s);
  const int cols = depth.cols, rows = depth.rows;
  auto valid = [&](int u, int r) {
    const float d = depth.at<float>(r, u);
    return d > 0.0f && std::isfinite(d);
  };
  // Depth at a fractional pixel: bilinear where the four neighbours lie on one surface (within
  // kSurfaceRatio of each other), else the nearest pixel's, so no point is invented between a
  // foreground and a background surface. Negative: no depth there.
  auto depthAt = [&](double su, double sr) -> double {
    const int u0 = static_cast<int>(std::floor(su)), r0 = static_cast<int>(std::floor(sr));
    if (u0 >= 0 && r0 >= 0 && u0 + 1 < cols && r0 + 1 < rows && valid(u0, r0) && valid(u0 + 1, r0) &&
        valid(u0, r0 + 1) && valid(u0 + 1, r0 + 1)) {
      const double d00 = depth.at<float>(r0, u0), d10 = depth.at<float>(r0, u0 + 1);
      const double d01 = depth.at<float>(r0 + 1, u0), d11 = depth.at<float>(r0 + 1, u0 + 1);
      const double lo = std::min({d00, d10, d01, d11}), hi = std::max({d00, d10, d01, d11});
      if (hi - lo <= kSurfaceRatio * lo) {
        const double fu = su - u0, fr = sr - r0;
        return (d00 * (1 - fu) + d10 * fu) * (1 - fr) + (d01 * (1 - fu) + d11 * fu) * fr;
      }
    }
    const int iu = static_cast<int>(std::lround(su)), ir = static_cast<int>(std::lround(sr));
    if (iu < 0 || ir < 0 || iu >= cols || ir >= rows || !valid(iu, ir)) return -1.0;
    return depth.at<float>(ir, iu);
  };
  // Where the scene point seen at source position (su, sr) lands at the stamp's pose.
  auto warp = [&](double su, double sr, double& x, double& y, double& z) {
    const double d = depthAt(su, sr);
    if (d <= 0.0) return false;
    const auto& m = motions[static_cast<std::size_t>(std::clamp<long>(std::lround(sr), 0, rows - 1))];
    const Eigen::Vector3d p = m.R * k.unproject(su, sr, d) + m.t;
    if (!k.project(p, x, y)) return false;
    z = p.z();
    return true;
  };

  cv::Mat out(depth.size(), CV_32FC1, cv::Scalar(0.0f));
  for (int r = 0; r < rows; ++r) {
    for (int u = 0; u < cols; ++u) {
      // The source position whose point lands on (u, r): fixed-point iteration, the warp being
      // close to the identity (a few pixels of shift that change slowly across the image).
      double su = u, sr = r, x = 0, y = 0, z = 0;
      bool found = false;
      for (int it = 0; it < kIterations; ++it) {
        if (!warp(su, sr, x, y, z)) break;
        if (std::abs(x - u) <= kConvergedPx && std::abs(y - r) <= kConvergedPx) {
          found = true;
          break;
        }
        su += u - x;
        sr += r - y;
      }
      if (found) out.at<float>(r, u) = static_cast<float>(z);
    }
  }
  return out;
}

}  // namespace gasp
