#include "gasp/core/rolling_shutter.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
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

Isometry3 twistMotion(const CameraTwist& twist, double dt_s) {
  const double w = twist.w_radps.norm();
  Isometry3 T = Isometry3::Identity();
  if (w > 0.0) T.linear() = Eigen::AngleAxisd(w * dt_s, twist.w_radps / w).toRotationMatrix();
  T.translation() = twist.v_mps * dt_s;
  return T;
}

namespace {

/// The pose of the camera at row r relative to the stamp's: exp([w dt]), v dt.
struct RowMotion {
  Eigen::Matrix3d R;
  Eigen::Vector3d t;
};

std::vector<RowMotion> rowMotions(int rows, const CameraTwist& twist, double readout_s) {
  std::vector<RowMotion> motions(static_cast<std::size_t>(rows));
  for (int r = 0; r < rows; ++r) {
    const double dt = (rows > 1 ? static_cast<double>(r) / (rows - 1) - 0.5 : 0.0) * readout_s;
    const Isometry3 T = twistMotion(twist, dt);
    motions[static_cast<std::size_t>(r)] = {T.linear(), T.translation()};
  }
  return motions;
}

constexpr double kSurfaceRatio = 0.03;  ///< neighbours within 3 % of depth: one surface
constexpr int kIterations = 8;
constexpr double kConvergedPx = 0.05;
constexpr int kSeedRadiusPx = 8;  ///< where to look for a starting shift when (u, r) has no depth

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

  // Forward pass: where each source pixel's point lands at the stamp's pose (dx, dy: the shift
  // in pixels) and its depth there (z; 0 = no depth or behind the camera).
  cv::Mat dx(depth.size(), CV_32FC1), dy(depth.size(), CV_32FC1), z(depth.size(), CV_32FC1, cv::Scalar(0.0f));
  cv::parallel_for_(cv::Range(0, rows), [&](const cv::Range& range) {
    for (int r = range.start; r < range.end; ++r) {
      const auto& m = motions[static_cast<std::size_t>(r)];
      const float* d_row = depth.ptr<float>(r);
      float *dx_row = dx.ptr<float>(r), *dy_row = dy.ptr<float>(r), *z_row = z.ptr<float>(r);
      for (int u = 0; u < cols; ++u) {
        const float d = d_row[u];
        if (!(d > 0.0f) || !std::isfinite(d)) continue;
        const Eigen::Vector3d p = m.R * k.unproject(u, r, d) + m.t;
        double x = 0, y = 0;
        if (!k.project(p, x, y)) continue;
        // A point carried to (or behind) the camera plane lands nowhere useful: no depth.
        if (!(std::abs(x - u) < cols && std::abs(y - r) < rows)) continue;
        dx_row[u] = static_cast<float>(x - u);
        dy_row[u] = static_cast<float>(y - r);
        z_row[u] = static_cast<float>(p.z());
      }
    }
  });

  // The forward maps at a fractional source position: bilinear where the four neighbouring
  // pixels lie on one surface (depths within kSurfaceRatio of each other), else the nearest
  // pixel's, so that no point is invented between a foreground and a background surface.
  struct Sample {
    double shift_u, shift_v, depth;
  };
  auto sampleAt = [&](double su, double sr, Sample& out) {
    if (!(su > -1.0 && sr > -1.0 && su < cols && sr < rows)) return false;  // also NaN
    const int u0 = static_cast<int>(std::floor(su)), r0 = static_cast<int>(std::floor(sr));
    if (u0 >= 0 && r0 >= 0 && u0 + 1 < cols && r0 + 1 < rows) {
      const float z00 = z.at<float>(r0, u0), z10 = z.at<float>(r0, u0 + 1);
      const float z01 = z.at<float>(r0 + 1, u0), z11 = z.at<float>(r0 + 1, u0 + 1);
      const float lo = std::min({z00, z10, z01, z11}), hi = std::max({z00, z10, z01, z11});
      if (lo > 0.0f && hi - lo <= kSurfaceRatio * lo) {
        const double fu = su - u0, fr = sr - r0;
        const double w00 = (1 - fu) * (1 - fr), w10 = fu * (1 - fr), w01 = (1 - fu) * fr, w11 = fu * fr;
        auto blend = [&](const cv::Mat& map) {
          return w00 * map.at<float>(r0, u0) + w10 * map.at<float>(r0, u0 + 1) + w01 * map.at<float>(r0 + 1, u0) +
                 w11 * map.at<float>(r0 + 1, u0 + 1);
        };
        out = {blend(dx), blend(dy), w00 * z00 + w10 * z10 + w01 * z01 + w11 * z11};
        return true;
      }
    }
    const int iu = static_cast<int>(std::lround(su)), ir = static_cast<int>(std::lround(sr));
    if (iu < 0 || ir < 0 || iu >= cols || ir >= rows || !(z.at<float>(ir, iu) > 0.0f)) return false;
    out = {dx.at<float>(ir, iu), dy.at<float>(ir, iu), z.at<float>(ir, iu)};
    return true;
  };

  auto seedFromNeighbour = [&](int u, int r, double& su, double& sr) {
    for (int d = 1; d <= kSeedRadiusPx; ++d)
      for (const auto& [nu, nr] : {std::pair{u - d, r}, std::pair{u + d, r}, std::pair{u, r - d}, std::pair{u, r + d}}) {
        if (nu < 0 || nr < 0 || nu >= cols || nr >= rows || !(z.at<float>(nr, nu) > 0.0f)) continue;
        su = u - dx.at<float>(nr, nu);
        sr = r - dy.at<float>(nr, nu);
        return;
      }
  };

  // Inverse: the source position s whose point lands on target pixel (u, r), by fixed-point
  // iteration s <- (u, r) - shift(s); the shift is a few pixels and changes slowly within a surface.
  cv::Mat out(depth.size(), CV_32FC1, cv::Scalar(0.0f));
  cv::parallel_for_(cv::Range(0, rows), [&](const cv::Range& range) {
    for (int r = range.start; r < range.end; ++r) {
      float* out_row = out.ptr<float>(r);
      for (int u = 0; u < cols; ++u) {
        double su = u, sr = r;
        // Without depth at (u, r) itself, start from the shift of the nearest pixel with depth
        // on the same row or column: the source of (u, r) may have depth where (u, r) has none.
        if (!(z.at<float>(r, u) > 0.0f)) seedFromNeighbour(u, r, su, sr);
        Sample sample{};
        for (int it = 0; it < kIterations; ++it) {
          if (!sampleAt(su, sr, sample)) break;
          const double miss_u = u - (su + sample.shift_u), miss_v = r - (sr + sample.shift_v);
          if (std::abs(miss_u) <= kConvergedPx && std::abs(miss_v) <= kConvergedPx) {
            out_row[u] = static_cast<float>(sample.depth);
            break;
          }
          su += miss_u;
          sr += miss_v;
        }
      }
    }
  });
  return out;
}

}  // namespace gasp
