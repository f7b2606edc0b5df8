#include "gasp/superpixels/area_kmeans.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "pixel_area.h"

namespace gasp {

namespace {

struct Cluster {
  Eigen::Vector3f centre = Eigen::Vector3f::Zero();
  Eigen::Vector3f normal = Eigen::Vector3f::Zero();
};

/// Uniform double in [0, 1) from 53 random bits (same on every platform, unlike
/// std::uniform_real_distribution).
/// A centre searches pixels within this many patch radii (projected) of it; SLIC uses about 1.8
/// (twice the grid step S ~ sqrt(pi) R, as a full width).
constexpr double kWindowRadii = 1.8;
/// Image bucket size [px] of the seeds' spatial index.
constexpr int kBucket = 16;

double uniform01(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

}  // namespace

AreaPatches splitIntoAreaPatches(const cv::Mat& region_labels, int num_regions,
                                 const OrganizedPointCloud& cloud, const SurfaceNormals& normals,
                                 const CameraIntrinsics& k, const SuperpixelParams& p) {
  const int w = cloud.width, h = cloud.height;
  const std::size_t n_px = static_cast<std::size_t>(w) * h;
  const float min_cos = static_cast<float>(std::cos(p.max_incidence_deg * M_PI / 180.0));
  const float radius = static_cast<float>(std::sqrt(p.target_patch_area_m2 / M_PI));
  const float inv_r2 = 1.0f / (radius * radius);
  const float w_n = static_cast<float>(p.kmeans_normal_weight);

  // Flat views of the per-pixel data (all matrices are continuous, row-major).
  const int* region = region_labels.ptr<int>(0);
  const int* has_normal = normals.radius.ptr<int>(0);
  const auto* normal_px = reinterpret_cast<const Eigen::Vector3f*>(normals.normals.ptr<float>(0));
  auto normalAt = [&](int i) -> const Eigen::Vector3f& { return normal_px[i]; };
  // Clustering runs on the window-averaged points: raw Kinect points far away are noisier than a
  // patch is wide, which would fray the cells.
  const auto* point = reinterpret_cast<const Eigen::Vector3f*>(normals.smoothed.ptr<float>(0));

  // Pixels of each region, in raster order (CSR layout).
  std::vector<int> start(static_cast<std::size_t>(num_regions) + 1, 0);
  for (std::size_t i = 0; i < n_px; ++i)
    if (region[i] >= 0) ++start[static_cast<std::size_t>(region[i]) + 1];
  for (int r = 0; r < num_regions; ++r) start[r + 1] += start[r];
  std::vector<int> members(static_cast<std::size_t>(start.back()));
  {
    std::vector<int> fill(start.begin(), start.end() - 1);
    for (int i = 0; i < static_cast<int>(n_px); ++i)
      if (region[i] >= 0) members[static_cast<std::size_t>(fill[region[i]]++)] = i;
  }

  AreaPatches out;
  out.labels = cv::Mat(h, w, CV_32S, cv::Scalar(-1));
  std::vector<float> area(n_px, 0.0f), best(n_px, 0.0f);
  const int buckets_x = (w + kBucket - 1) / kBucket, buckets_y = (h + kBucket - 1) / kBucket;
  std::vector<std::vector<int>> buckets(static_cast<std::size_t>(buckets_x * buckets_y));
  std::vector<int> assign(n_px, -1);

  for (int r = 0; r < num_regions; ++r) {
    const int* first = members.data() + start[r];
    const int n = start[r + 1] - start[r];
    if (n == 0) continue;
    double total_area = 0.0;
    for (int j = 0; j < n; ++j) {
      const int i = first[j];
      area[i] = detail::pixelArea(point[i], normalAt(i), k, min_cos);
      total_area += area[i];
    }
    int K = std::max(1, static_cast<int>(std::lround(total_area / p.target_patch_area_m2)));
    if (K == 1) {
      for (int j = 0; j < n; ++j) out.labels.at<int>(first[j] / w, first[j] % w) = out.count;
      ++out.count;
      continue;
    }

    // ---- Seeds spread uniformly over the surface: Poisson-disk dart throwing in a seeded random
    //      order (each accepted seed at least d_min from all others in 3D). Random sequential
    //      packing covers ~54.7% of the plane with discs of diameter d_min, so d_min is chosen for
    //      about K seeds: 0.547 * A / (pi d_min^2 / 4) = A / A_t.
    std::vector<int> cand;
    const int step = std::max(1, p.seed_sampling_step_px);
    for (int j = 0; j < n; ++j) {
      const int i = first[j];
      if ((i % w) % step == 0 && (i / w) % step == 0) cand.push_back(i);
    }
    if (static_cast<int>(cand.size()) < 4 * K) cand.assign(first, first + n);
    std::mt19937_64 rng(p.seed * 0x9E3779B97F4A7C15ULL + static_cast<std::uint64_t>(r) + 1);
    for (std::size_t j = cand.size(); j > 1; --j)  // Fisher-Yates with a portable index draw
      std::swap(cand[j - 1], cand[static_cast<std::size_t>(uniform01(rng) * static_cast<double>(j))]);
    const float d_min = static_cast<float>(std::sqrt(0.547 * 4.0 / M_PI * p.target_patch_area_m2));
    std::vector<Cluster> clusters;
    std::vector<int> touched;
    for (const int i : cand) {
      const Eigen::Vector3f& q = point[i];
      const int u = i % w, v = i / w;
      const float reach = static_cast<float>(k.fx) * d_min / std::max(q.z() - d_min, 0.05f);
      const int b0 = std::max(0, static_cast<int>((u - reach) / kBucket)),
                b1 = std::min(buckets_x - 1, static_cast<int>((u + reach) / kBucket));
      const int c0 = std::max(0, static_cast<int>((v - reach) / kBucket)),
                c1 = std::min(buckets_y - 1, static_cast<int>((v + reach) / kBucket));
      bool free = true;
      for (int by = c0; by <= c1 && free; ++by)
        for (int bx = b0; bx <= b1 && free; ++bx)
          for (const int s : buckets[static_cast<std::size_t>(by * buckets_x + bx)])
            if ((clusters[static_cast<std::size_t>(s)].centre - q).squaredNorm() < d_min * d_min) {
              free = false;
              break;
            }
      if (!free) continue;
      const std::size_t b = static_cast<std::size_t>((v / kBucket) * buckets_x + u / kBucket);
      if (buckets[b].empty()) touched.push_back(static_cast<int>(b));
      buckets[b].push_back(static_cast<int>(clusters.size()));
      Cluster c;
      c.centre = q;
      c.normal = normalAt(i);
      clusters.push_back(c);
    }
    for (const int b : touched) buckets[static_cast<std::size_t>(b)].clear();

    // ---- Lloyd iterations with windowed assignment, on every second pixel in each direction
    //      (4x fewer pixels), then one full-resolution assignment to the converged centres.
    const int iterations = std::max(1, p.kmeans_iterations);
    for (int it = 0; it <= iterations; ++it) {
      const bool final_pass = it == iterations;
      const int stride = final_pass ? 1 : 2;
      for (int j = 0; j < n; ++j) {
        best[first[j]] = std::numeric_limits<float>::infinity();
        assign[first[j]] = -1;
      }
      for (int c = 0; c < static_cast<int>(clusters.size()); ++c) {
        const Cluster& cl = clusters[c];
        double uc = 0, vc = 0;
        if (!k.project(cl.centre.cast<double>(), uc, vc)) continue;
        const int win = std::min(200, static_cast<int>(std::ceil(kWindowRadii * radius * k.fx / cl.centre.z())) + 1);
        int u0 = std::max(0, static_cast<int>(uc) - win), v0 = std::max(0, static_cast<int>(vc) - win);
        const int u1 = std::min(w - 1, static_cast<int>(uc) + win), v1 = std::min(h - 1, static_cast<int>(vc) + win);
        u0 += u0 % stride;
        v0 += v0 % stride;
        for (int v = v0; v <= v1; v += stride) {
          for (int i = v * w + u0; i <= v * w + u1; i += stride) {
            if (region[i] != r) continue;
            float d = (point[i] - cl.centre).squaredNorm() * inv_r2;
            if (has_normal[i] > 0) d += w_n * (1.0f - normalAt(i).dot(cl.normal));
            if (d < best[i]) {
              best[i] = d;
              assign[i] = c;
            }
          }
        }
      }
      if (final_pass) break;
      // Area-weighted centres.
      std::vector<Eigen::Vector3d> sum_p(clusters.size(), Eigen::Vector3d::Zero());
      std::vector<Eigen::Vector3d> sum_n(clusters.size(), Eigen::Vector3d::Zero());
      std::vector<double> sum_a(clusters.size(), 0.0);
      for (int j = 0; j < n; ++j) {
        const int i = first[j], c = assign[i];
        if (c < 0) continue;
        sum_p[c] += area[i] * point[i].cast<double>();
        sum_n[c] += area[i] * normalAt(i).cast<double>();
        sum_a[c] += area[i];
      }
      for (std::size_t c = 0; c < clusters.size(); ++c) {
        if (sum_a[c] <= 0.0) continue;  // keeps its centre; no pixel at the end -> no patch
        clusters[c].centre = (sum_p[c] / sum_a[c]).cast<float>();
        if (sum_n[c].norm() > 0) clusters[c].normal = sum_n[c].normalized().cast<float>();
      }
    }
    std::vector<int> id(clusters.size(), -1);
    for (int j = 0; j < n; ++j) {
      const int i = first[j], c = assign[i];
      if (c < 0) continue;
      if (id[c] < 0) id[c] = out.count++;
      out.labels.at<int>(i / w, i % w) = id[c];
    }
  }
  return out;
}

}  // namespace gasp
