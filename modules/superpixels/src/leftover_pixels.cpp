#include "leftover_pixels.h"

#include <algorithm>
#include <utility>

#include "pixel_area.h"

namespace gasp::detail {

// There are few leftover pixels and small patches: this works on their pixels, scanning the image
// only when there are small patches.
void settleLeftoverPixels(int* L, int count, std::vector<PlaneModel>& models, const OrganizedPointCloud& cloud,
                          const DepthLinks& links, const PixelNormals& N, const ViewProjection& k,
                          const SuperpixelParams& p, float min_cos, const std::vector<int>& unlabelled) {
  const int n_px = cloud.width * cloud.height;
  const int old_count = count;
  const PixelArea pixel_area(k, min_cos);
  std::vector<char> small(static_cast<std::size_t>(count), 0);
  bool any_small = false;
  for (int c = 0; c < count; ++c)
    if (models[c].pixels > 0 && models[c].pixels < p.cleanup.min_patch_pixels) small[c] = 1, any_small = true;
  std::vector<int> pixels_of_small;  // raster order
  for (int i = 0; i < n_px && any_small; ++i)
    if (L[i] >= 0 && small[L[i]]) pixels_of_small.push_back(i);
  // New labels for the linked groups of unlabelled pixels (flood fill), after the existing ones.
  std::vector<std::pair<int, int>> members;  // (label, pixel), by group
  std::vector<int> stack;
  for (const int i : unlabelled) {
    if (L[i] >= 0) continue;
    const int g = count++;
    L[i] = g;
    stack.push_back(i);
    while (!stack.empty()) {
      const int j = stack.back();
      stack.pop_back();
      members.emplace_back(g, j);
      links.forEachNeighbour(j, [&](int n) {
        if (L[n] < 0) L[n] = g, stack.push_back(n);
      });
    }
  }
  if (count == old_count && !any_small) return;
  // Models of the new groups; adjacency of every candidate.
  models.resize(static_cast<std::size_t>(count));
  std::vector<Eigen::Vector3d> sum_p(static_cast<std::size_t>(count - old_count), Eigen::Vector3d::Zero());
  std::vector<Eigen::Vector3d> sum_n(sum_p.size(), Eigen::Vector3d::Zero());
  std::vector<std::pair<int, int>> pairs;
  auto neighbours = [&](int l, int i) {
    links.forEachNeighbour(i, [&](int j) {
      if (L[j] >= 0 && L[j] != l) pairs.emplace_back(l, L[j]);
    });
  };
  for (const auto& [l, i] : members) {
    const std::size_t g = static_cast<std::size_t>(l - old_count);
    sum_p[g] += cloud.points[static_cast<std::size_t>(i)].cast<double>();
    sum_n[g] += N(i).cast<double>();
    ++models[static_cast<std::size_t>(l)].pixels;
    neighbours(l, i);
  }
  for (const int i : pixels_of_small) neighbours(L[i], i);
  for (int c = old_count; c < count; ++c) {
    PlaneModel& m = models[static_cast<std::size_t>(c)];
    const std::size_t g = static_cast<std::size_t>(c - old_count);
    m.centroid = (sum_p[g] / m.pixels).cast<float>();
    m.normal = sum_n[g].norm() > 0 ? sum_n[g].normalized().cast<float>() : (-m.centroid).normalized();
  }
  for (const auto& [l, i] : members)
    models[static_cast<std::size_t>(l)].area +=
        pixel_area(cloud.points[static_cast<std::size_t>(i)], models[static_cast<std::size_t>(l)].normal);
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  std::vector<int> order;
  for (int c = 0; c < count; ++c)
    if (c >= old_count || small[c]) order.push_back(c);
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    return std::make_pair(models[a].pixels, a) < std::make_pair(models[b].pixels, b);
  });
  std::vector<int> target(static_cast<std::size_t>(count));
  for (int c = 0; c < count; ++c) target[c] = c;
  auto resolve = [&](int c) {
    while (c >= 0 && target[c] != c) c = target[c];
    return c;
  };
  const float min_area = static_cast<float>(p.cleanup.min_patch_area_ratio * p.target_patch_area_m2);
  for (const int c : order) {
    const bool too_small = models[c].pixels < p.cleanup.min_patch_pixels || (c >= old_count && models[c].area < min_area);
    if (!too_small) continue;
    int best = -1;
    float best_score = -2.0f;
    for (auto it = std::lower_bound(pairs.begin(), pairs.end(), std::make_pair(c, -1));
         it != pairs.end() && it->first == c; ++it) {
      const int nb = resolve(it->second);
      if (nb < 0 || nb == c) continue;
      const float score = models[c].normal.dot(models[nb].normal);
      if (score > best_score || (score == best_score && nb < best)) best_score = score, best = nb;
    }
    if (best >= 0) {
      target[c] = best;
      models[best].pixels += models[c].pixels;
    } else if (models[c].pixels < p.cleanup.min_patch_pixels) {
      target[c] = -1;  // isolated speck: noise
    }
  }
  for (const auto& [l, i] : members) L[i] = resolve(l);
  for (const int i : pixels_of_small) L[i] = resolve(L[i]);
}


}  // namespace gasp::detail
