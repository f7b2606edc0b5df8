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

SmoothComponents segmentSmoothComponents(const DepthLinks& links, const SurfaceNormals& normals,
                                         const SuperpixelParams& p) {
  const int w = links.width(), h = links.height();
  const float max_crease = static_cast<float>(p.surfaces.max_crease_angle_deg * M_PI / 180.0);
  const float min_dot = static_cast<float>(std::cos(p.surfaces.max_neighbour_normal_angle_deg * M_PI / 180.0));
  const int* radius = normals.radius.ptr<int>(0);
  const float* crease = normals.crease.ptr<float>(0);
  const cv::Vec3f* n = normals.normals.ptr<cv::Vec3f>(0);
  std::vector<std::uint8_t> core(static_cast<std::size_t>(w) * h);
  for (int i = 0; i < w * h; ++i) core[i] = radius[i] > 0 && crease[i] <= max_crease;

  detail::DisjointSets sets(static_cast<std::size_t>(w) * h);
  links.forEachLink([&](int a, int b) {
    if (core[a] && core[b] && n[a].dot(n[b]) >= min_dot) sets.unite(a, b);
  });
  std::vector<int> size(static_cast<std::size_t>(w) * h, 0);
  for (int i = 0; i < w * h; ++i)
    if (core[i]) ++size[static_cast<std::size_t>(sets.find(i))];
  SmoothComponents out;
  out.labels = cv::Mat(h, w, CV_32S, cv::Scalar(-1));
  int* L = out.labels.ptr<int>(0);
  for (int i = 0; i < w * h; ++i) {
    if (!core[i]) continue;
    const int root = sets.find(i);
    if (size[static_cast<std::size_t>(root)] >= p.surfaces.min_component_pixels) L[i] = root;
  }
  out.count = relabelInRasterOrder(out.labels);
  return out;
}

}  // namespace gasp
