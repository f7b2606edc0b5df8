#include "gasp/superpixels/patch_cleanup.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "disjoint_sets.h"
#include "gasp/superpixels/area_kmeans.h"
#include "gasp/superpixels/smooth_components.h"
#include "pixel_area.h"

namespace gasp {

namespace {

struct PlaneModel {
  Eigen::Vector3f centroid = Eigen::Vector3f::Zero();
  Eigen::Vector3f normal = Eigen::Vector3f::Zero();
  float area = 0.0f;
  int pixels = 0;
};

/// 1. Keep the largest depth-connected piece of each label.
void enforceContiguity(cv::Mat& labels, const DepthLinks& links) {
  int* L = labels.ptr<int>(0);
  const std::size_t n_px = labels.total();
  detail::DisjointSets sets(n_px);
  links.forEachLink([&](int a, int b) {
    if (L[a] >= 0 && L[a] == L[b]) sets.unite(a, b);
  });
  std::vector<int> piece_size(n_px, 0);
  for (std::size_t i = 0; i < n_px; ++i)
    if (L[i] >= 0) ++piece_size[static_cast<std::size_t>(sets.find(static_cast<int>(i)))];
  int max_label = -1;
  for (std::size_t i = 0; i < n_px; ++i) max_label = std::max(max_label, L[i]);
  std::vector<int> best_root(static_cast<std::size_t>(max_label + 1), -1);  // largest piece per label
  for (std::size_t i = 0; i < n_px; ++i) {
    if (L[i] < 0) continue;
    const int root = sets.find(static_cast<int>(i));
    int& best = best_root[static_cast<std::size_t>(L[i])];
    if (best < 0 || piece_size[root] > piece_size[best] ||
        (piece_size[root] == piece_size[best] && root < best))
      best = root;
  }
  for (std::size_t i = 0; i < n_px; ++i)
    if (L[i] >= 0 && sets.find(static_cast<int>(i)) != best_root[static_cast<std::size_t>(L[i])]) L[i] = -1;
}

std::vector<PlaneModel> planeModels(const cv::Mat& labels, int count, const OrganizedPointCloud& cloud,
                                    const SurfaceNormals& normals, const CameraIntrinsics& k,
                                    float min_cos) {
  std::vector<PlaneModel> m(static_cast<std::size_t>(count));
  std::vector<Eigen::Vector3d> sum_p(m.size(), Eigen::Vector3d::Zero()), sum_n(m.size(), Eigen::Vector3d::Zero());
  const int w = cloud.width;
  const int* L = labels.ptr<int>(0);
  for (std::size_t i = 0, n_px = labels.total(); i < n_px; ++i) {
    if (L[i] < 0) continue;
    const int u = static_cast<int>(i) % w, v = static_cast<int>(i) / w;
    auto& pm = m[static_cast<std::size_t>(L[i])];
    sum_p[L[i]] += cloud.points[i].cast<double>();
    ++pm.pixels;
    if (normals.hasNormal(u, v)) {
      const cv::Vec3f& n = normals.normals.at<cv::Vec3f>(v, u);
      sum_n[L[i]] += Eigen::Vector3d(n[0], n[1], n[2]);
    }
  }
  for (std::size_t c = 0; c < m.size(); ++c) {
    if (m[c].pixels == 0) continue;
    m[c].centroid = (sum_p[c] / m[c].pixels).cast<float>();
    m[c].normal = sum_n[c].norm() > 0 ? sum_n[c].normalized().cast<float>()
                                      : (-m[c].centroid).normalized();
  }
  for (std::size_t i = 0, n_px = labels.total(); i < n_px; ++i)
    if (L[i] >= 0) {
      auto& pm = m[static_cast<std::size_t>(L[i])];
      pm.area += detail::pixelArea(cloud.points[i], pm.normal, k, min_cos);
    }
  return m;
}

/// 2. Priority region growing of unlabelled valid pixels into adjacent patches.
void regrowLeftovers(cv::Mat& labels, int count, const OrganizedPointCloud& cloud,
                     const DepthLinks& links, const SurfaceNormals& normals, const CameraIntrinsics& k, const SuperpixelParams& p,
                     float min_cos, float area_cap_ratio, float cost_radii) {
  const int w = cloud.width, h = cloud.height;
  int* L = labels.ptr<int>(0);
  auto models = planeModels(labels, count, cloud, normals, k, min_cos);
  // A patch stops growing at area_cap_ratio x the target area; what is left becomes new patches
  // (step 3).
  const float max_area = static_cast<float>(area_cap_ratio * p.target_patch_area_m2);
  const float max_cost = cost_radii * static_cast<float>(std::sqrt(p.target_patch_area_m2 / M_PI));
  const float w_n = static_cast<float>(p.regrow_normal_weight_m);
  const int* has_normal = normals.radius.ptr<int>(0);
  const auto* normal_px = reinterpret_cast<const Eigen::Vector3f*>(normals.normals.ptr<float>(0));
  auto cost = [&](int i, int label) {
    const PlaneModel& m = models[static_cast<std::size_t>(label)];
    float c = std::abs(m.normal.dot(cloud.points[static_cast<std::size_t>(i)] - m.centroid));
    if (has_normal[i] > 0) c += w_n * (1.0f - std::abs(m.normal.dot(normal_px[i])));
    return c;
  };
  // Bucket queue over the cost range [0, max_cost]: O(1) push and pop; within a bucket, last in
  // first out. Deterministic; costs closer than max_cost / kBuckets may be taken out of order.
  constexpr int kBuckets = 256;
  std::vector<std::vector<std::pair<int, int>>> buckets(kBuckets);  // (pixel, label)
  int lowest = kBuckets;
  auto pushNeighbours = [&](int i) {
    links.forEachNeighbour(i, [&](int j) {
      if (L[j] >= 0) return;
      const float c = cost(j, L[i]);
      if (c > max_cost) return;
      const int b = std::min(kBuckets - 1, static_cast<int>(c / max_cost * kBuckets));
      buckets[static_cast<std::size_t>(b)].emplace_back(j, L[i]);
      lowest = std::min(lowest, b);
    });
  };
  for (int i = 0; i < w * h; ++i)
    if (L[i] >= 0) pushNeighbours(i);
  while (lowest < kBuckets) {
    auto& bucket = buckets[static_cast<std::size_t>(lowest)];
    if (bucket.empty()) {
      ++lowest;
      continue;
    }
    const auto [i, label] = bucket.back();
    bucket.pop_back();
    if (L[i] >= 0) continue;
    PlaneModel& m = models[static_cast<std::size_t>(label)];
    if (m.area >= max_area) continue;
    m.area += detail::pixelArea(cloud.points[static_cast<std::size_t>(i)], m.normal, k, min_cos);
    L[i] = label;
    pushNeighbours(i);
  }
}

/// 4. Merge patches below the minimum size into their most similar neighbour.
void mergeSmallPatches(cv::Mat& labels, int count, const OrganizedPointCloud& cloud,
                       const DepthLinks& links, const SurfaceNormals& normals, const CameraIntrinsics& k,
                       const SuperpixelParams& p, float min_cos) {
  int* L = labels.ptr<int>(0);
  auto models = planeModels(labels, count, cloud, normals, k, min_cos);
  std::vector<std::set<int>> adjacent(static_cast<std::size_t>(count));
  links.forEachLink([&](int a, int b) {
    if (L[a] >= 0 && L[b] >= 0 && L[a] != L[b]) {
      adjacent[L[a]].insert(L[b]);
      adjacent[L[b]].insert(L[a]);
    }
  });
  const float min_area = static_cast<float>(p.min_patch_area_ratio * p.target_patch_area_m2);
  auto isSmall = [&](int c) {
    return models[c].pixels > 0 && (models[c].pixels < p.min_patch_pixels || models[c].area < min_area);
  };
  std::vector<int> target(static_cast<std::size_t>(count));
  for (int c = 0; c < count; ++c) target[c] = c;
  // Smallest first; a merged patch's statistics are updated so chains of small pieces combine.
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
      if (models[c].pixels < p.min_patch_pixels) {
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
  auto resolve = [&](int c) {
    while (c >= 0 && target[c] != c) c = target[c];
    return c;
  };
  for (std::size_t i = 0, n_px = labels.total(); i < n_px; ++i)
    if (L[i] >= 0) L[i] = resolve(L[i]);
}

}  // namespace

int cleanUpPatches(cv::Mat& labels, const OrganizedPointCloud& cloud, const DepthLinks& links,
                   const SurfaceNormals& normals, const CameraIntrinsics& k, const SuperpixelParams& p) {
  const float min_cos = static_cast<float>(std::cos(p.max_incidence_deg * M_PI / 180.0));
  int count = relabelInRasterOrder(labels);
  enforceContiguity(labels, links);
  count = relabelInRasterOrder(labels);
  // First pass: patches grow up to twice the target area, within one patch radius of their plane.
  regrowLeftovers(labels, count, cloud, links, normals, k, p, min_cos, 2.0f, 1.0f);
  // Second pass, for what is left next to patches (crease bands of far, noisy surfaces):
  // up to three times the area and two radii from the plane.
  regrowLeftovers(labels, count, cloud, links, normals, k, p, min_cos, 3.0f, 2.0f);

  // 3. Leftover depth-connected groups become regions of their own, split by area like surfaces.
  {
    const int w = cloud.width, h = cloud.height;
    const int* L = labels.ptr<int>(0);
    detail::DisjointSets sets(labels.total());
    links.forEachLink([&](int a, int b) {
      if (L[a] < 0 && L[b] < 0) sets.unite(a, b);
    });
    cv::Mat groups(h, w, CV_32S, cv::Scalar(-1));
    int* G = groups.ptr<int>(0);
    for (int i = 0; i < w * h; ++i)
      if (L[i] < 0 && links.valid(i)) G[i] = sets.find(i);
    const int n_groups = relabelInRasterOrder(groups);
    if (n_groups > 0) {
      AreaPatches extra = splitIntoAreaPatches(groups, n_groups, cloud, normals, k, p);
      enforceContiguity(extra.labels, links);
      for (int i = 0; i < w * h; ++i) {
        const int e = extra.labels.at<int>(i / w, i % w);
        if (e >= 0) labels.at<int>(i / w, i % w) = count + e;
      }
      count = relabelInRasterOrder(labels);
    }
  }
  mergeSmallPatches(labels, count, cloud, links, normals, k, p, min_cos);
  return relabelInRasterOrder(labels);
}

}  // namespace gasp
