#include "gasp/superpixels/patch_cleanup.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include "contiguity.h"
#include "gasp/superpixels/area_kmeans.h"
#include "gasp/superpixels/smooth_components.h"
#include "pixel_area.h"
#include "region_growing.h"

namespace gasp {

namespace {

using detail::PlaneModel;

/// 4. Merge patches below the minimum size into their most similar neighbour (edge contraction on
/// the patch graph, smallest first, so chains of small pieces combine).
void mergeSmallPatches(cv::Mat& labels, int count, std::vector<PlaneModel> models, const DepthLinks& links,
                       const SuperpixelParams& p) {
  int* L = labels.ptr<int>(0);
  // Adjacency from the label pairs across links, deduplicated before the sets are built.
  std::vector<std::pair<int, int>> pairs;
  std::pair<int, int> last_right{-1, -1}, last_down{-1, -1};  // a border repeats its pair
  const int w = links.width();
  links.forEachLink([&](int a, int b) {
    if (L[a] < 0 || L[b] < 0 || L[a] == L[b]) return;
    const std::pair<int, int> pair(std::min(L[a], L[b]), std::max(L[a], L[b]));
    std::pair<int, int>& last = b == a + 1 && w > 1 ? last_right : last_down;
    if (pair == last) return;
    last = pair;
    pairs.push_back(pair);
  });
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  std::vector<std::set<int>> adjacent(static_cast<std::size_t>(count));
  for (const auto& [a, b] : pairs) {
    adjacent[a].insert(b);
    adjacent[b].insert(a);
  }
  const float min_area = static_cast<float>(p.cleanup.min_patch_area_ratio * p.target_patch_area_m2);
  auto isSmall = [&](int c) {
    return models[c].pixels > 0 && (models[c].pixels < p.cleanup.min_patch_pixels || models[c].area < min_area);
  };
  std::vector<int> target(static_cast<std::size_t>(count));
  for (int c = 0; c < count; ++c) target[c] = c;
  std::vector<int> order(static_cast<std::size_t>(count));
  for (int c = 0; c < count; ++c) order[c] = c;
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    return std::make_pair(models[a].area, a) < std::make_pair(models[b].area, b);
  });
  for (int c : order) {
    if (!isSmall(c)) continue;
    int best = -1;
    float best_score = -2.0f;
    for (int nb : adjacent[c]) {
      const float s = models[c].normal.dot(models[nb].normal);
      if (s > best_score || (s == best_score && nb < best)) {
        best_score = s;
        best = nb;
      }
    }
    if (best < 0) {
      if (models[c].pixels < p.cleanup.min_patch_pixels) {
        target[c] = -1;  // isolated speck: dropped
        models[c].pixels = 0;
      }
      continue;
    }
    // Contract edge (c, best): c's pixels and neighbours go to best.
    auto& mb = models[best];
    const auto& mc = models[c];
    const float total = static_cast<float>(mb.pixels + mc.pixels);
    mb.centroid = (mb.centroid * static_cast<float>(mb.pixels) + mc.centroid * static_cast<float>(mc.pixels)) / total;
    mb.normal = (mb.normal * mb.area + mc.normal * mc.area).normalized();
    mb.area += mc.area;
    mb.pixels += mc.pixels;
    models[c].pixels = 0;
    target[c] = best;
    for (int nb : adjacent[c]) {
      adjacent[nb].erase(c);
      if (nb != best) {
        adjacent[nb].insert(best);
        adjacent[best].insert(nb);
      }
    }
    adjacent[c].clear();
  }
  // Resolve merge chains once per label, not per pixel.
  for (int c = 0; c < count; ++c) {
    int t = c;
    while (t >= 0 && target[t] != t) t = target[t];
    target[c] = t;
  }
  for (std::size_t i = 0, n_px = labels.total(); i < n_px; ++i)
    if (L[i] >= 0) L[i] = target[L[i]];
}

/// 3. Linked groups of unlabelled valid pixels (flood fill: there are few) become new patches:
/// small groups as they are, larger ones split by the area k-means on a crop around them.
/// Returns the new patch count.
int splitLeftovers(cv::Mat& labels, int count, const OrganizedPointCloud& cloud, const DepthLinks& links,
                   const SurfaceNormals& normals, const ViewProjection& k, const SuperpixelParams& p, float min_cos) {
  const int w = cloud.width, n_px = w * cloud.height;
  int* L = labels.ptr<int>(0);
  const auto* pixel_normals = reinterpret_cast<const Eigen::Vector3f*>(normals.normals.ptr<float>(0));
  const detail::PixelArea pixel_area(k, min_cos);
  std::vector<int> group, stack;
  for (int i0 = 0; i0 < n_px; ++i0) {
    if (L[i0] >= 0 || !links.valid(i0)) continue;
    // Flood fill with a temporary label below -1, so the group is not visited twice.
    group.clear();
    L[i0] = -2;
    stack.push_back(i0);
    double area = 0.0;
    int u0 = w, v0 = cloud.height, u1 = -1, v1 = -1;
    while (!stack.empty()) {
      const int i = stack.back();
      stack.pop_back();
      group.push_back(i);
      const Eigen::Vector3f& n = pixel_normals[i];
      area += pixel_area(cloud.points[static_cast<std::size_t>(i)], n);
      u0 = std::min(u0, i % w), u1 = std::max(u1, i % w), v0 = std::min(v0, i / w), v1 = std::max(v1, i / w);
      links.forEachNeighbour(i, [&](int j) {
        if (L[j] == -1) L[j] = -2, stack.push_back(j);
      });
    }
    if (area < 1.5 * p.target_patch_area_m2) {  // one patch (the k-means would give K = 1)
      for (const int i : group) L[i] = count;
      ++count;
      continue;
    }
    // The k-means on the group's bounding box: the cloud, normals and intrinsics cut to it.
    const cv::Rect box(u0, v0, u1 - u0 + 1, v1 - v0 + 1);
    OrganizedPointCloud crop;
    crop.width = box.width, crop.height = box.height, crop.range_depth = cloud.range_depth;
    crop.points.reserve(static_cast<std::size_t>(box.area()));
    for (int v = v0; v <= v1; ++v)
      crop.points.insert(crop.points.end(), cloud.points.begin() + v * w + u0, cloud.points.begin() + v * w + u1 + 1);
    SurfaceNormals cn;
    cn.normals = normals.normals(box).clone(), cn.crease = normals.crease(box).clone();
    cn.radius = normals.radius(box).clone(), cn.smoothed = normals.smoothed(box).clone();
    const ViewProjection kc = k.cropped(u0, v0, box.width, box.height);
    cv::Mat region(box.size(), CV_32S, cv::Scalar(-1));
    for (const int i : group) region.at<int>(i / w - v0, i % w - u0) = 0;
    AreaPatches parts = splitIntoAreaPatches(region, 1, crop, cn, kc, p);
    detail::keepLargestPieces(parts.labels, DepthLinks(crop, p));
    for (const int i : group) {
      const int part = parts.labels.at<int>(i / w - v0, i % w - u0);
      L[i] = part >= 0 ? count + part : -1;  // cut-off pieces and pixels no centre reached: none
    }
    count += parts.count;
  }
  for (std::size_t i = 0; i < static_cast<std::size_t>(n_px); ++i)
    if (L[i] < -1) L[i] = -1;
  return count;
}

}  // namespace

int cleanUpPatches(cv::Mat& labels, const OrganizedPointCloud& cloud, const DepthLinks& links,
                   const SurfaceNormals& normals, const ViewProjection& k, const SuperpixelParams& p) {
  const float min_cos = static_cast<float>(std::cos(p.max_incidence_deg * M_PI / 180.0));
  const std::size_t n_px = labels.total();
  int* L = labels.ptr<int>(0);
  const Eigen::Vector3f* points = cloud.points.data();
  const auto* pixel_normals = reinterpret_cast<const Eigen::Vector3f*>(normals.normals.ptr<float>(0));
  const float radius = static_cast<float>(std::sqrt(p.target_patch_area_m2 / M_PI));
  const float w_n = static_cast<float>(p.cleanup.regrow_normal_weight_m);

  // 1. Contiguity.
  detail::keepLargestPieces(labels, links);
  int count = relabelInRasterOrder(labels);
  // 2. Growth into the pixels set aside (crease and edge bands, small components): up to three
  //    times the target area and two patch radii from the plane, cheapest first over the whole
  //    image. (A first, tighter pass -- one radius, twice the area -- made no difference once the
  //    full-resolution labelling re-decides the band borders; docs/superpixels.md.)
  {
    auto models = detail::planeModels(L, n_px, count, points, pixel_normals, k, min_cos);
    const detail::GrowthLimits limits{2.0f * radius, 3.0f * static_cast<float>(p.target_patch_area_m2), w_n};
    detail::growPatches(L, links, points, detail::PixelNormals{pixel_normals}, models, limits, k, min_cos);
  }

  // 3. Leftover depth-connected groups become patches of their own, split by area like surfaces.
  count = splitLeftovers(labels, count, cloud, links, normals, k, p, min_cos);
  // 4. Small patches.
  mergeSmallPatches(labels, count, detail::planeModels(L, n_px, count, points, pixel_normals, k, min_cos), links, p);
  return relabelInRasterOrder(labels);
}

}  // namespace gasp
