#include "gasp/superpixels/normals.h"

#include <Eigen/Geometry>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "gasp/core/error.h"

namespace gasp {

namespace {

/// acos to within 7e-5 rad (Abramowitz & Stegun 4.4.45): the crease angle is only compared with
/// a threshold of tens of degrees, and std::acos costs more than the rest of the crease pass.
float fastAcos(float x) {
  const float a = std::min(std::abs(x), 1.0f);
  const float r = std::sqrt(1.0f - a) * (1.5707288f + a * (-0.2121144f + a * (0.0742610f - 0.0187293f * a)));
  return x >= 0.0f ? r : static_cast<float>(M_PI) - r;
}

}  // namespace

SurfaceNormals estimateNormals(const OrganizedPointCloud& cloud, const DepthLinks& links,
                               const SuperpixelParams& p) {
  const int w = cloud.width, h = cloud.height;
  if (w <= 0 || h <= 0 || cloud.points.size() != static_cast<std::size_t>(w) * h)
    throw Error("estimateNormals: empty or inconsistent organised cloud");
  const std::size_t n_px = static_cast<std::size_t>(w) * h;
  SurfaceNormals out;
  out.normals = cv::Mat(h, w, CV_32FC3, cv::Scalar(0, 0, 0));
  out.crease = cv::Mat(h, w, CV_32F, cv::Scalar(std::nanf("")));
  out.radius = cv::Mat(h, w, CV_32S, cv::Scalar(0));
  out.smoothed = cv::Mat(h, w, CV_32FC3);
  auto* smoothed = reinterpret_cast<Eigen::Vector3f*>(out.smoothed.ptr<float>(0));
  std::copy(cloud.points.begin(), cloud.points.end(), smoothed);

  // Chessboard distance to the nearest pixel that is invalid or next to a discontinuity: a
  // window of half-size d - 1 then holds only points of one smooth surface.
  cv::Mat interior(h, w, CV_8U);
  for (std::size_t i = 0; i < n_px; ++i) interior.data[i] = links.interior(static_cast<int>(i)) ? 255 : 0;
  cv::Mat dist;
  cv::distanceTransform(interior, dist, cv::DIST_C, 3, CV_32F);

  // Integral image of the points, (h+1) x (w+1) x 3, in double: window means subtract large sums.
  // Invalid points count as zero (windows never contain one).
  const int stride = w + 1;
  // Not zero-filled (every entry is written below): that would only cost page-touching time.
  const std::unique_ptr<double[]> sums(new double[static_cast<std::size_t>(stride) * (h + 1) * 3]);
  double* const S = sums.get();
  std::fill(S, S + static_cast<std::size_t>(stride) * 3, 0.0);  // row 0
  for (int v = 0; v < h; ++v) {
    const Eigen::Vector3f* q = cloud.points.data() + static_cast<std::size_t>(v) * w;
    const double* above = S + static_cast<std::size_t>(v) * stride * 3;
    double* row = S + static_cast<std::size_t>(v + 1) * stride * 3;
    row[0] = row[1] = row[2] = 0.0;  // column 0
    double sx = 0, sy = 0, sz = 0;
    for (int u = 0; u < w; ++u) {
      if (std::isfinite(q[u].z())) {
        sx += q[u].x();
        sy += q[u].y();
        sz += q[u].z();
      }
      row[3 * (u + 1) + 0] = above[3 * (u + 1) + 0] + sx;
      row[3 * (u + 1) + 1] = above[3 * (u + 1) + 1] + sy;
      row[3 * (u + 1) + 2] = above[3 * (u + 1) + 2] + sz;
    }
  }
  auto* N = reinterpret_cast<Eigen::Vector3f*>(out.normals.ptr<float>(0));
  int* R = out.radius.ptr<int>(0);
  const double px_per_m = p.surfaces.normal_window_px_per_m;
  for (int v = 0; v < h; ++v) {
    const float* d = dist.ptr<float>(v);
    for (int u = 0; u < w; ++u) {
      if (d[u] < 1.0f) continue;
      const std::size_t i = static_cast<std::size_t>(v) * w + u;
      const Eigen::Vector3f& q = cloud.points[i];
      int r = static_cast<int>(px_per_m * cloud.depth(q) + 0.5);
      r = std::clamp(r, p.surfaces.normal_min_radius_px, p.surfaces.normal_max_radius_px);
      r = std::min({r, static_cast<int>(d[u]) - 1, u, v, w - 1 - u, h - 1 - v});  // stay inside
      if (r < p.surfaces.normal_min_radius_px) continue;
      // Integral-image corners: rows v - r, v, v + 1, v + r + 1 and columns u - r, u, u + 1,
      // u + r + 1 (12 of the 16 are used). Right minus left half (dx), below minus above (dy), and
      // the whole window, each as sums over its rectangle.
      const int rows[4] = {v - r, v, v + 1, v + r + 1}, cols[4] = {u - r, u, u + 1, u + r + 1};
      auto S3 = [&](int a, int b) { return S + (static_cast<std::size_t>(rows[a]) * stride + cols[b]) * 3; };
      Eigen::Vector3d dx, dy, all;
      for (int c = 0; c < 3; ++c) {
        const double s00 = S3(0, 0)[c], s01 = S3(0, 1)[c], s02 = S3(0, 2)[c], s03 = S3(0, 3)[c];
        const double s10 = S3(1, 0)[c], s13 = S3(1, 3)[c], s20 = S3(2, 0)[c], s23 = S3(2, 3)[c];
        const double s30 = S3(3, 0)[c], s31 = S3(3, 1)[c], s32 = S3(3, 2)[c], s33 = S3(3, 3)[c];
        const double right = s33 - s03 - s32 + s02, left = s31 - s01 - s30 + s00;
        const double below = s33 - s23 - s30 + s20, above = s13 - s03 - s10 + s00;
        dx[c] = right - left, dy[c] = below - above, all[c] = s33 - s03 - s30 + s00;
      }
      // The common 1 / half-window area does not change the direction. The differences needed
      // double (large sums cancel); the normal itself does not: float, one reciprocal.
      Eigen::Vector3f n = dy.cross(dx).cast<float>();
      const float len2 = n.squaredNorm();
      if (!(len2 > 0.0f)) continue;
      n *= (n.dot(q) > 0.0f ? -1.0f : 1.0f) / std::sqrt(len2);  // unit, facing the camera
      N[i] = n;
      R[i] = r;
      smoothed[i] = (all * (1.0 / static_cast<double>((2 * r + 1) * (2 * r + 1)))).cast<float>();
    }
  }

  // Crease measure: angle between the normals half a window left/right and above/below the
  // pixel (the larger); catches creases that have no depth discontinuity.
  float* C = out.crease.ptr<float>(0);
  for (int v = 0; v < h; ++v) {
    for (int u = 0; u < w; ++u) {
      const int i = v * w + u;
      const int r = R[i];
      if (r == 0) continue;
      // Half the window apart: the band set aside around a crease stays about one window wide.
      const int step = std::max(1, r / 2);
      auto cosAcross = [&](int a, int b) {
        const Eigen::Vector3f& na = R[a] > 0 ? N[a] : N[i];
        const Eigen::Vector3f& nb = R[b] > 0 ? N[b] : N[i];
        return na.dot(nb);
      };
      C[i] = fastAcos(std::min(cosAcross(i - step, i + step), cosAcross(i - step * w, i + step * w)));
    }
  }
  return out;
}

}  // namespace gasp
