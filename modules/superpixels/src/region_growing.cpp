#include "region_growing.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "pixel_area.h"

namespace gasp::detail {

std::vector<PlaneModel> planeModels(const int* L, std::size_t n_px, int count, const Eigen::Vector3f* points,
                                    const Eigen::Vector3f* normals, const ViewProjection& k, float min_cos,
                                    bool with_area) {
  std::vector<PlaneModel> m(static_cast<std::size_t>(count));
  struct Sum {
    double x = 0, y = 0, z = 0, nx = 0, ny = 0, nz = 0;
    int n = 0;
  };
  std::vector<Sum> sums(m.size());
  // Neighbouring pixels mostly share a label: sum a run in registers, then add it.
  Sum run;
  int run_label = -1;
  auto flush = [&] {
    if (run_label < 0) return;
    Sum& s = sums[static_cast<std::size_t>(run_label)];
    s.x += run.x, s.y += run.y, s.z += run.z, s.nx += run.nx, s.ny += run.ny, s.nz += run.nz, s.n += run.n;
  };
  for (std::size_t i = 0; i < n_px; ++i) {
    const int l = L[i];
    if (l < 0) continue;
    if (l != run_label) flush(), run = Sum{}, run_label = l;
    run.x += points[i].x(), run.y += points[i].y(), run.z += points[i].z();
    run.nx += normals[i].x(), run.ny += normals[i].y(), run.nz += normals[i].z();
    ++run.n;
  }
  flush();
  for (std::size_t c = 0; c < m.size(); ++c) {
    const Sum& s = sums[c];
    m[c].pixels = s.n;
    if (s.n == 0) continue;
    m[c].centroid = Eigen::Vector3d(s.x / s.n, s.y / s.n, s.z / s.n).cast<float>();
    const Eigen::Vector3d n(s.nx, s.ny, s.nz);
    m[c].normal = n.norm() > 0 ? n.normalized().cast<float>() : (-m[c].centroid).normalized();
  }
  const PixelArea pixel_area(k, min_cos);
  float run_area = 0.0f;
  run_label = -1;
  for (std::size_t i = 0; i < n_px && with_area; ++i) {
    const int l = L[i];
    if (l < 0) continue;
    if (l != run_label) {
      if (run_label >= 0) m[static_cast<std::size_t>(run_label)].area += run_area;
      run_area = 0.0f, run_label = l;
    }
    run_area += pixel_area(points[i], m[static_cast<std::size_t>(l)].normal);
  }
  if (run_label >= 0) m[static_cast<std::size_t>(run_label)].area += run_area;
  return m;
}

int growPatches(int* L, const DepthLinks& links, const Eigen::Vector3f* points, const PixelNormals& normals,
                std::vector<PlaneModel>& models, const GrowthLimits& lim, const ViewProjection& k, float min_cos,
                const std::vector<int>* unlabelled) {
  const int n_px = links.width() * links.height();
  const bool area_limit = std::isfinite(lim.max_area);
  const PixelArea pixel_area(k, min_cos);
  auto cost = [&](int i, int label) {
    const PlaneModel& m = models[static_cast<std::size_t>(label)];
    float c = std::abs(m.normal.dot(points[i] - m.centroid));
    const Eigen::Vector3f n = normals(i);
    if (n.x() != 0.0f || n.y() != 0.0f || n.z() != 0.0f) c += lim.normal_weight_m * (1.0f - std::abs(m.normal.dot(n)));
    return c;
  };
  // Bucket queue over the cost range [0, max_cost]: O(1) push and pop; within a bucket, last in
  // first out. Deterministic; costs closer than max_cost / kBuckets may be taken out of order.
  constexpr int kBuckets = 256;
  std::vector<std::vector<std::pair<int, int>>> buckets(kBuckets);  // (pixel, label)
  int lowest = kBuckets;
  // The label a pixel was last queued for: the same pair again would only repeat its cost (a
  // growth front pixel often touches several pixels of one patch).
  std::vector<int> queued_for(static_cast<std::size_t>(n_px), -1);
  auto push = [&](int j, int label) {
    int& last = queued_for[static_cast<std::size_t>(j)];
    if (last == label) return;
    last = label;
    const float c = cost(j, label);
    if (!(c <= lim.max_cost)) return;
    const int b = std::min(kBuckets - 1, static_cast<int>(c / lim.max_cost * kBuckets));
    buckets[static_cast<std::size_t>(b)].emplace_back(j, label);
    lowest = std::min(lowest, b);
  };
  // Seeds: every unlabelled valid pixel next to a patch, once per adjacent patch side.
  auto seed = [&](int j) {
    if (L[j] >= 0 || !links.valid(j)) return;
    links.forEachNeighbour(j, [&](int i) {
      if (L[i] >= 0) push(j, L[i]);
    });
  };
  if (unlabelled) {
    for (const int j : *unlabelled) seed(j);
  } else {
    for (int j = 0; j < n_px; ++j) seed(j);
  }
  int grown = 0;
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
    if (area_limit) {
      if (m.area >= lim.max_area) continue;
      m.area += pixel_area(points[i], m.normal);
    }
    L[i] = label;
    ++m.pixels;
    ++grown;
    const auto grown_label = label;  // a structured binding cannot be captured before C++20 (clang 14)
    links.forEachNeighbour(i, [&](int j) {
      if (L[j] < 0) push(j, grown_label);
    });
  }
  return grown;
}

}  // namespace gasp::detail
