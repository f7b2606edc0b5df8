#include "gasp/superpixels/smooth_components.h"

#include <cmath>
#include <algorithm>
#include <vector>

#include "disjoint_sets.h"

namespace gasp {

int relabelInRasterOrder(cv::Mat& labels) {
  int max_label = -1;
  int* L = labels.ptr<int>(0);
  const std::size_t n = labels.total();
  for (std::size_t i = 0; i < n; ++i) max_label = std::max(max_label, L[i]);
  std::vector<int> remap(static_cast<std::size_t>(max_label + 1), -1);
  int next = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (L[i] < 0) continue;
    int& m = remap[static_cast<std::size_t>(L[i])];
    if (m < 0) m = next++;
    L[i] = m;
  }
  return next;
}

SmoothComponents segmentSmoothComponents(const OrganizedPointCloud& cloud,
                                         const SurfaceNormals& normals,
                                         const SuperpixelParams& p) {
  const int w = cloud.width, h = cloud.height;
  const float max_crease = static_cast<float>(p.max_crease_angle_deg * M_PI / 180.0);
  const float min_dot = static_cast<float>(std::cos(p.max_neighbour_normal_angle_deg * M_PI / 180.0));
  cv::Mat core(h, w, CV_8U, cv::Scalar(0));
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u)
      core.at<std::uint8_t>(v, u) = normals.hasNormal(u, v) && normals.crease.at<float>(v, u) <= max_crease;

  detail::DisjointSets sets(static_cast<std::size_t>(w) * h);
  auto joinable = [&](int ua, int va, int ub, int vb) {
    return core.at<std::uint8_t>(vb, ub) &&
           depthConnected(cloud.at(ua, va).z(), cloud.at(ub, vb).z(), p) &&
           normals.normals.at<cv::Vec3f>(va, ua).dot(normals.normals.at<cv::Vec3f>(vb, ub)) >= min_dot;
  };
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u) {
      if (!core.at<std::uint8_t>(v, u)) continue;
      const int i = v * w + u;
      if (u + 1 < w && joinable(u, v, u + 1, v)) sets.unite(i, i + 1);
      if (v + 1 < h && joinable(u, v, u, v + 1)) sets.unite(i, i + w);
    }

  SmoothComponents out;
  out.labels = cv::Mat(h, w, CV_32S, cv::Scalar(-1));
  std::vector<int> size(static_cast<std::size_t>(w) * h, 0);
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u)
      if (core.at<std::uint8_t>(v, u)) ++size[static_cast<std::size_t>(sets.find(v * w + u))];
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u) {
      if (!core.at<std::uint8_t>(v, u)) continue;
      const int root = sets.find(v * w + u);
      if (size[static_cast<std::size_t>(root)] >= p.min_component_pixels) out.labels.at<int>(v, u) = root;
    }
  out.count = relabelInRasterOrder(out.labels);
  return out;
}

}  // namespace gasp
