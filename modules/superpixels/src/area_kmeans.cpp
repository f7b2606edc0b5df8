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
  bool alive = true;
};

/// Uniform double in [0, 1) from 53 random bits (same on every platform, unlike
/// std::uniform_real_distribution).
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

  auto normalAt = [&](int i) -> Eigen::Vector3f {
    const cv::Vec3f& n = normals.normals.at<cv::Vec3f>(i / w, i % w);
    return {n[0], n[1], n[2]};
  };

  // Pixels of each region, in raster order (CSR layout).
  std::vector<int> start(static_cast<std::size_t>(num_regions) + 1, 0);
  for (int i = 0; i < static_cast<int>(n_px); ++i) {
    const int r = region_labels.at<int>(i / w, i % w);
    if (r >= 0) ++start[static_cast<std::size_t>(r) + 1];
  }
  for (int r = 0; r < num_regions; ++r) start[r + 1] += start[r];
  std::vector<int> members(static_cast<std::size_t>(start.back()));
  {
    std::vector<int> fill(start.begin(), start.end() - 1);
    for (int i = 0; i < static_cast<int>(n_px); ++i) {
      const int r = region_labels.at<int>(i / w, i % w);
      if (r >= 0) members[static_cast<std::size_t>(fill[r]++)] = i;
    }
  }

  AreaPatches out;
  out.labels = cv::Mat(h, w, CV_32S, cv::Scalar(-1));
  std::vector<float> area(n_px, 0.0f), best(n_px, 0.0f);
  std::vector<int> assign(n_px, -1);

  for (int r = 0; r < num_regions; ++r) {
    const int* first = members.data() + start[r];
    const int n = start[r + 1] - start[r];
    if (n == 0) continue;
    double total_area = 0.0;
    for (int j = 0; j < n; ++j) {
      const int i = first[j];
      area[i] = detail::pixelArea(cloud.points[i], normalAt(i), k, min_cos);
      total_area += area[i];
    }
    int K = std::max(1, static_cast<int>(std::lround(total_area / p.target_patch_area_m2)));
    if (K == 1) {
      for (int j = 0; j < n; ++j) out.labels.at<int>(first[j] / w, first[j] % w) = out.count;
      ++out.count;
      continue;
    }

    // ---- k-means++ seeding over a subsample of the surface (D^2 x pixel area).
    std::vector<int> cand;
    const int step = std::max(1, p.seed_sampling_step_px);
    for (int j = 0; j < n; ++j) {
      const int i = first[j];
      if ((i % w) % step == 0 && (i / w) % step == 0) cand.push_back(i);
    }
    if (static_cast<int>(cand.size()) < 2 * K) cand.assign(first, first + n);
    K = std::min(K, static_cast<int>(cand.size()));
    std::mt19937_64 rng(p.seed * 0x9E3779B97F4A7C15ULL + static_cast<std::uint64_t>(r) + 1);
    std::vector<float> d2(cand.size(), std::numeric_limits<float>::infinity());
    std::vector<Cluster> clusters;
    auto addSeed = [&](int i) {
      Cluster c;
      c.centre = cloud.points[i];
      c.normal = normalAt(i);
      clusters.push_back(c);
      for (std::size_t j = 0; j < cand.size(); ++j)
        d2[j] = std::min(d2[j], (cloud.points[cand[j]] - c.centre).squaredNorm());
    };
    auto sample = [&](bool weighted_by_d2) {
      double sum = 0.0;
      for (std::size_t j = 0; j < cand.size(); ++j) sum += area[cand[j]] * (weighted_by_d2 ? d2[j] : 1.0f);
      if (!(sum > 0.0)) return -1;
      double x = uniform01(rng) * sum;
      for (std::size_t j = 0; j < cand.size(); ++j) {
        x -= area[cand[j]] * (weighted_by_d2 ? d2[j] : 1.0f);
        if (x <= 0.0) return cand[j];
      }
      return cand.back();
    };
    addSeed(sample(false));
    while (static_cast<int>(clusters.size()) < K) {
      const int i = sample(true);
      if (i < 0) break;
      addSeed(i);
    }

    // ---- Lloyd iterations with windowed assignment.
    for (int it = 0; it < std::max(1, p.kmeans_iterations); ++it) {
      for (int j = 0; j < n; ++j) {
        best[first[j]] = std::numeric_limits<float>::infinity();
        assign[first[j]] = -1;
      }
      for (int c = 0; c < static_cast<int>(clusters.size()); ++c) {
        const Cluster& cl = clusters[c];
        if (!cl.alive) continue;
        double uc = 0, vc = 0;
        if (!k.project(cl.centre.cast<double>(), uc, vc)) continue;
        const int win = std::min(200, static_cast<int>(std::ceil(2.0 * radius * k.fx / cl.centre.z())) + 1);
        const int u0 = std::max(0, static_cast<int>(uc) - win), u1 = std::min(w - 1, static_cast<int>(uc) + win);
        const int v0 = std::max(0, static_cast<int>(vc) - win), v1 = std::min(h - 1, static_cast<int>(vc) + win);
        for (int v = v0; v <= v1; ++v) {
          const int* reg = region_labels.ptr<int>(v);
          for (int u = u0; u <= u1; ++u) {
            if (reg[u] != r) continue;
            const int i = v * w + u;
            float d = (cloud.points[i] - cl.centre).squaredNorm() * inv_r2;
            if (normals.radius.at<int>(v, u) > 0) d += w_n * (1.0f - normalAt(i).dot(cl.normal));
            if (d < best[i]) {
              best[i] = d;
              assign[i] = c;
            }
          }
        }
      }
      // Area-weighted centres; clusters that won no pixel die.
      std::vector<Eigen::Vector3d> sum_p(clusters.size(), Eigen::Vector3d::Zero());
      std::vector<Eigen::Vector3d> sum_n(clusters.size(), Eigen::Vector3d::Zero());
      std::vector<double> sum_a(clusters.size(), 0.0);
      for (int j = 0; j < n; ++j) {
        const int i = first[j], c = assign[i];
        if (c < 0) continue;
        sum_p[c] += area[i] * cloud.points[i].cast<double>();
        sum_n[c] += area[i] * normalAt(i).cast<double>();
        sum_a[c] += area[i];
      }
      for (std::size_t c = 0; c < clusters.size(); ++c) {
        if (sum_a[c] <= 0.0) {
          clusters[c].alive = false;
          continue;
        }
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
