#include "gasp/superpixels/normals.h"

#include <Eigen/Geometry>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>

#include "gasp/core/error.h"

namespace gasp {

SurfaceNormals estimateNormals(const OrganizedPointCloud& cloud, const DepthLinks& links,
                               const SuperpixelParams& p) {
  const int w = cloud.width, h = cloud.height;
  if (w <= 0 || h <= 0 || cloud.points.size() != static_cast<std::size_t>(w) * h)
    throw Error("estimateNormals: empty or inconsistent organised cloud");
  SurfaceNormals out;
  out.normals = cv::Mat(h, w, CV_32FC3, cv::Scalar(0, 0, 0));
  out.crease = cv::Mat(h, w, CV_32F, cv::Scalar(std::nanf("")));
  out.radius = cv::Mat(h, w, CV_32S, cv::Scalar(0));
  out.smoothed = cv::Mat(h, w, CV_32FC3);
  for (int i = 0; i < w * h; ++i) {
    const Eigen::Vector3f& q = cloud.points[static_cast<std::size_t>(i)];
    out.smoothed.ptr<cv::Vec3f>(0)[i] = cv::Vec3f(q.x(), q.y(), q.z());
  }

  // Chessboard distance to the nearest pixel that is invalid or next to a discontinuity: a
  // window of half-size d - 1 then holds only points of one smooth surface.
  cv::Mat interior(h, w, CV_8U);
  for (int i = 0; i < w * h; ++i) interior.data[i] = links.interior(i) ? 255 : 0;
  cv::Mat dist;
  cv::distanceTransform(interior, dist, cv::DIST_C, 3, CV_32F);

  cv::Mat xyz(h, w, CV_64FC3);
  for (int v = 0; v < h; ++v) {
    auto* row = xyz.ptr<cv::Vec3d>(v);
    for (int u = 0; u < w; ++u) {
      const Eigen::Vector3f& q = cloud.at(u, v);
      row[u] = q.allFinite() ? cv::Vec3d(q.x(), q.y(), q.z()) : cv::Vec3d(0, 0, 0);
    }
  }
  cv::Mat sum;  // (h+1) x (w+1), sum(r0..r1-1, c0..c1-1) = S(r1,c1) - S(r0,c1) - S(r1,c0) + S(r0,c0)
  cv::integral(xyz, sum, CV_64F);
  const auto* S = sum.ptr<cv::Vec3d>(0);
  const int stride = w + 1;
  auto box = [S, stride](int c0, int r0, int c1, int r1) {  // inclusive corners
    return S[(r1 + 1) * stride + c1 + 1] - S[r0 * stride + c1 + 1] - S[(r1 + 1) * stride + c0] +
           S[r0 * stride + c0];
  };

  for (int v = 0; v < h; ++v) {
    const float* d = dist.ptr<float>(v);
    auto* n_row = out.normals.ptr<cv::Vec3f>(v);
    auto* r_row = out.radius.ptr<int>(v);
    for (int u = 0; u < w; ++u) {
      if (d[u] < 1.0f) continue;
      const float z = cloud.at(u, v).z();
      int r = static_cast<int>(p.normal_window_px_per_m * z + 0.5);
      r = std::clamp(r, p.normal_min_radius_px, p.normal_max_radius_px);
      r = std::min({r, static_cast<int>(d[u]) - 1, u, v, w - 1 - u, h - 1 - v});  // stay inside
      if (r < p.normal_min_radius_px) continue;
      const double half = static_cast<double>(r) * (2 * r + 1);
      const cv::Vec3d dx = (box(u + 1, v - r, u + r, v + r) - box(u - r, v - r, u - 1, v + r)) / half;
      const cv::Vec3d dy = (box(u - r, v + 1, u + r, v + r) - box(u - r, v - r, u + r, v - 1)) / half;
      Eigen::Vector3d n = Eigen::Vector3d(dy[0], dy[1], dy[2]).cross(Eigen::Vector3d(dx[0], dx[1], dx[2]));
      const double len = n.norm();
      if (!(len > 0.0)) continue;
      n /= len;
      if (n.dot(cloud.at(u, v).cast<double>()) > 0.0) n = -n;  // face the camera
      n_row[u] = cv::Vec3f(static_cast<float>(n.x()), static_cast<float>(n.y()), static_cast<float>(n.z()));
      r_row[u] = r;
      out.smoothed.at<cv::Vec3f>(v, u) = box(u - r, v - r, u + r, v + r) / static_cast<double>((2 * r + 1) * (2 * r + 1));
    }
  }

  // Crease measure: angle between the normals half a window left/right and above/below the
  // pixel (the larger); catches creases that have no depth discontinuity.
  const int* R = out.radius.ptr<int>(0);
  const cv::Vec3f* N = out.normals.ptr<cv::Vec3f>(0);
  float* C = out.crease.ptr<float>(0);
  for (int v = 0; v < h; ++v) {
    for (int u = 0; u < w; ++u) {
      const int i = v * w + u;
      const int r = R[i];
      if (r == 0) continue;
      float min_dot = 1.0f;
      auto compare = [&](int a, int b) {
        const cv::Vec3f& na = R[a] > 0 ? N[a] : N[i];
        const cv::Vec3f& nb = R[b] > 0 ? N[b] : N[i];
        min_dot = std::min(min_dot, na.dot(nb));
      };
      // Half the window apart: the band set aside around a crease stays about one window wide.
      const int step = std::max(1, r / 2);
      compare(i - step, i + step);
      compare(i - step * w, i + step * w);
      C[i] = std::acos(std::clamp(min_dot, -1.0f, 1.0f));
    }
  }
  return out;
}

}  // namespace gasp
