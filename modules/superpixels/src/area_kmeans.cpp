#include "gasp/superpixels/area_kmeans.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <random>

#include "pixel_area.h"

// x86-64 with GCC or Clang: an AVX2 clone of the hottest loop, chosen at load time (ifunc).
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__)) && defined(__linux__)
#define GASP_AVX2_CLONE __attribute__((target_clones("avx2", "default")))
#else
#define GASP_AVX2_CLONE
#endif

namespace gasp {

namespace {

/// A centre searches pixels within this many patch radii (projected) of it. SLIC uses about 1.8
/// (twice the grid step S ~ sqrt(pi) R, as a full width); the cells here stay within about 1.5
/// radii of their centres (1.6 gives the same labels as 1.8 on every test frame; 1.4 starts to
/// differ), and 1.6 evaluates a fifth fewer distances.
constexpr double kWindowRadii = 1.6;

/// Uniform double in [0, 1) from 53 random bits (same on every platform, unlike
/// std::uniform_real_distribution).
double uniform01(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

struct Cluster {
  Eigen::Vector3f centre = Eigen::Vector3f::Zero();
  Eigen::Vector3f normal = Eigen::Vector3f::Zero();
  int region = -1;
};

struct Box {
  int u0 = std::numeric_limits<int>::max(), v0 = std::numeric_limits<int>::max(), u1 = -1, v1 = -1;
};

/// Pixels of each region in raster order (CSR layout: members[start[r] .. start[r + 1])) and each
/// region's bounding box.
struct Regions {
  std::vector<int> start, members;
  std::vector<Box> boxes;
};

Regions indexRegions(const int* region, int w, int h, int num_regions) {
  Regions g;
  g.start.assign(static_cast<std::size_t>(num_regions) + 1, 0);
  g.boxes.resize(static_cast<std::size_t>(num_regions));
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u) {
      const int r = region[v * w + u];
      if (r < 0) continue;
      ++g.start[static_cast<std::size_t>(r) + 1];
      Box& b = g.boxes[static_cast<std::size_t>(r)];
      b.u0 = std::min(b.u0, u), b.u1 = std::max(b.u1, u), b.v0 = std::min(b.v0, v), b.v1 = std::max(b.v1, v);
    }
  for (int r = 0; r < num_regions; ++r) g.start[r + 1] += g.start[r];
  g.members.resize(static_cast<std::size_t>(g.start.back()));
  std::vector<int> fill(g.start.begin(), g.start.end() - 1);
  for (int i = 0; i < w * h; ++i)
    if (region[i] >= 0) g.members[static_cast<std::size_t>(fill[region[i]]++)] = i;
  return g;
}

/// Poisson-disk seeds of region r: dart throwing in a seeded random order, each accepted seed at
/// least d_min from all others in 3D. Random sequential packing covers ~54.7% of the plane with
/// discs of diameter d_min, so d_min is chosen for about K seeds: 0.547 A / (pi d_min^2 / 4) =
/// A / A_t. An accepted seed marks the pixels of its region it covers (within d_min, searched over
/// its projected reach), so a candidate is tested by one look-up.
void seedRegion(int r, const int* first, int n, int K, const int* region, const Eigen::Vector3f* point,
                const Eigen::Vector3f* normal, int w, int h, const ViewProjection& k, const SuperpixelParams& p,
                std::vector<Cluster>& clusters, std::vector<int>& covered) {
  std::vector<int> cand;
  const int step = std::max(1, p.kmeans.seed_sampling_step_px);
  for (int j = 0; j < n && step > 1; ++j) {
    const int i = first[j];
    if ((i % w) % step == 0 && (i / w) % step == 0) cand.push_back(i);
  }
  if (static_cast<int>(cand.size()) < 4 * K) cand.assign(first, first + n);
  std::mt19937_64 rng(p.kmeans.seed * 0x9E3779B97F4A7C15ULL + static_cast<std::uint64_t>(r) + 1);
  for (std::size_t j = cand.size(); j > 1; --j)  // Fisher-Yates with a portable index draw
    std::swap(cand[j - 1], cand[static_cast<std::size_t>(uniform01(rng) * static_cast<double>(j))]);
  const float d_min = static_cast<float>(std::sqrt(0.547 * 4.0 / M_PI * p.target_patch_area_m2));
  const float d2 = d_min * d_min;
  for (const int i : cand) {
    if (covered[static_cast<std::size_t>(i)] == r) continue;
    const Eigen::Vector3f& q = point[i];
    clusters.push_back({q, normal[i], r});
    const int u = i % w, v = i / w;
    const float reach = static_cast<float>(k.pixelsPerRadian()) * d_min / std::max(k.depth(q) - d_min, 0.05f);
    const int u0 = std::max(0, static_cast<int>(u - reach)), u1 = std::min(w - 1, static_cast<int>(u + reach));
    const int v0 = std::max(0, static_cast<int>(v - reach)), v1 = std::min(h - 1, static_cast<int>(v + reach));
    for (int y = v0; y <= v1; ++y)
      for (int x = u0; x <= u1; ++x) {
        const int j = y * w + x;
        if (region[j] == r && (point[j] - q).squaredNorm() < d2) covered[static_cast<std::size_t>(j)] = r;
      }
  }
}

/// The pixels of every step-th row and column as separate arrays (contiguous, so the assignment
/// loop over a window row vectorises): window-averaged point, normal (zero where none), region,
/// area. Step 1 is the whole image.
struct Lattice {
  int step = 1, width = 0, height = 0;
  std::vector<float> x, y, z, nx, ny, nz, area;
  std::vector<int> region, members;  // members: lattice indices with a region, raster order

  Lattice(int s, int w, int h, const int* full_region, const Eigen::Vector3f* point, const Eigen::Vector3f* normal,
          const int* has_normal, const float* full_area)
      : step(s), width((w + s - 1) / s), height((h + s - 1) / s) {
    const std::size_t n = static_cast<std::size_t>(width) * height;
    x.assign(n, 0.0f), y.assign(n, 0.0f), z.assign(n, 0.0f), nx.assign(n, 0.0f), ny.assign(n, 0.0f),
        nz.assign(n, 0.0f), area.assign(n, 0.0f), region.assign(n, -1);
    for (int lv = 0; lv < height; ++lv)
      for (int lu = 0; lu < width; ++lu) {
        const int i = lv * s * w + lu * s, j = lv * width + lu;
        if (full_region[i] < 0) continue;
        region[j] = full_region[i];
        members.push_back(j);
        x[j] = point[i].x(), y[j] = point[i].y(), z[j] = point[i].z(), area[j] = full_area[i];
        if (has_normal[i] > 0) nx[j] = normal[i].x(), ny[j] = normal[i].y(), nz[j] = normal[i].z();
      }
  }
};

/// Offers cluster c (of region cl.region) to lattice pixels u0..u1 of lattice row `row`:
/// d = |q - c|^2 / R^2 + w_n (1 - n.n_c); the constant w_n is left out (and pixels without a normal
/// have n = 0), which changes no pixel's choice. Branch-free, so the compiler vectorises it; an
/// AVX2 clone is picked at run time where the CPU has it (same arithmetic, no FMA: same results).
GASP_AVX2_CLONE void assignRow(const Lattice& lat, std::size_t row, int u0, int u1, int c, const Cluster& cl, float w_n,
               float inv_r2, float* best_row, int* assign_row) {
  const float* __restrict X = lat.x.data() + row;
  const float* __restrict Y = lat.y.data() + row;
  const float* __restrict Z = lat.z.data() + row;
  const float* __restrict NX = lat.nx.data() + row;
  const float* __restrict NY = lat.ny.data() + row;
  const float* __restrict NZ = lat.nz.data() + row;
  const int* __restrict G = lat.region.data() + row;
  float* __restrict best = best_row;
  int* __restrict assign = assign_row;
  const int label = cl.region;
  const float cx = cl.centre.x(), cy = cl.centre.y(), cz = cl.centre.z();
  const float ncx = w_n * cl.normal.x(), ncy = w_n * cl.normal.y(), ncz = w_n * cl.normal.z();
  for (int u = u0; u <= u1; ++u) {
    const float dx = X[u] - cx, dy = Y[u] - cy, dz = Z[u] - cz;
    const float d = (dx * dx + dy * dy + dz * dz) * inv_r2 - (NX[u] * ncx + NY[u] * ncy + NZ[u] * ncz);
    const bool take = (G[u] == label) & (d < best[u]);
    best[u] = take ? d : best[u];
    assign[u] = take ? c : assign[u];
  }
}

/// Assigns every lattice pixel to the closest cluster of its region whose window reaches it (-1
/// where none does); windows are kWindowRadii patch radii around the projected centres, cut to
/// the regions' bounding boxes.
void assignLattice(const Lattice& lat, const std::vector<Cluster>& clusters, const std::vector<Box>& boxes,
                   const ViewProjection& k, float radius, float w_n, std::vector<float>& best,
                   std::vector<int>& assign) {
  const int s = lat.step;
  best.assign(lat.region.size(), std::numeric_limits<float>::infinity());
  assign.assign(lat.region.size(), -1);
  const float inv_r2 = 1.0f / (radius * radius);
  for (int c = 0; c < static_cast<int>(clusters.size()); ++c) {
    const Cluster& cl = clusters[static_cast<std::size_t>(c)];
    double uc = 0, vc = 0;
    if (!k.project(cl.centre.cast<double>(), uc, vc)) continue;
    const int win = std::min(200, static_cast<int>(std::ceil(kWindowRadii * radius * k.pixelsPerRadian() / k.depth(cl.centre))));
    const Box& b = boxes[static_cast<std::size_t>(cl.region)];
    // Image window -> lattice columns and rows inside it.
    const int u0 = std::max(b.u0, static_cast<int>(uc) - win), v0 = std::max(b.v0, static_cast<int>(vc) - win);
    const int u1 = std::min(b.u1, static_cast<int>(uc) + win), v1 = std::min(b.v1, static_cast<int>(vc) + win);
    const int lu0 = (u0 + s - 1) / s, lv0 = (v0 + s - 1) / s;
    const int lu1 = std::min(lat.width - 1, u1 / s), lv1 = std::min(lat.height - 1, v1 / s);
    for (int lv = lv0; lv <= lv1; ++lv) {
      const std::size_t row = static_cast<std::size_t>(lv) * lat.width;
      assignRow(lat, row, lu0, lu1, c, cl, w_n, inv_r2, best.data() + row, assign.data() + row);
    }
  }
}

/// Area-weighted centres and normals of the clusters from the current assignment; a cluster that
/// got no pixel keeps its centre (no pixel at the end -> no patch).
void updateCentres(const Lattice& lat, const std::vector<int>& assign, std::vector<Cluster>& clusters) {
  struct Sum {
    double a = 0, x = 0, y = 0, z = 0, nx = 0, ny = 0, nz = 0;
  };
  std::vector<Sum> sums(clusters.size());
  // Consecutive pixels mostly belong to one cluster: sum a run in registers, then add it.
  Sum run;
  int run_cluster = -1;
  auto flush = [&] {
    if (run_cluster < 0) return;
    Sum& s = sums[static_cast<std::size_t>(run_cluster)];
    s.a += run.a, s.x += run.x, s.y += run.y, s.z += run.z, s.nx += run.nx, s.ny += run.ny, s.nz += run.nz;
  };
  for (const int j : lat.members) {
    const int c = assign[static_cast<std::size_t>(j)];
    if (c < 0) continue;
    if (c != run_cluster) flush(), run = Sum{}, run_cluster = c;
    const double a = lat.area[j];
    run.a += a;
    run.x += a * lat.x[j], run.y += a * lat.y[j], run.z += a * lat.z[j];
    run.nx += a * lat.nx[j], run.ny += a * lat.ny[j], run.nz += a * lat.nz[j];
  }
  flush();
  for (std::size_t c = 0; c < clusters.size(); ++c) {
    const Sum& s = sums[c];
    if (s.a <= 0.0) continue;
    clusters[c].centre = Eigen::Vector3d(s.x / s.a, s.y / s.a, s.z / s.a).cast<float>();
    const Eigen::Vector3d n(s.nx, s.ny, s.nz);
    if (n.norm() > 0) clusters[c].normal = n.normalized().cast<float>();
  }
}

}  // namespace

AreaPatches splitIntoAreaPatches(const cv::Mat& region_labels, int num_regions,
                                 const OrganizedPointCloud& cloud, const SurfaceNormals& normals,
                                 const ViewProjection& k, const SuperpixelParams& p) {
  const int w = cloud.width, h = cloud.height;
  const std::size_t n_px = static_cast<std::size_t>(w) * h;
  const float min_cos = static_cast<float>(std::cos(p.max_incidence_deg * M_PI / 180.0));
  const float radius = static_cast<float>(std::sqrt(p.target_patch_area_m2 / M_PI));
  const float w_n = static_cast<float>(p.kmeans.kmeans_normal_weight);

  // Flat views of the per-pixel data (all matrices are continuous, row-major).
  const int* region = region_labels.ptr<int>(0);
  const int* has_normal = normals.radius.ptr<int>(0);
  const auto* normal = reinterpret_cast<const Eigen::Vector3f*>(normals.normals.ptr<float>(0));
  // Clustering runs on the window-averaged points: raw Kinect points far away are noisier than a
  // patch is wide, which would fray the cells.
  const auto* point = reinterpret_cast<const Eigen::Vector3f*>(normals.smoothed.ptr<float>(0));
  const Regions regions = indexRegions(region, w, h, num_regions);
  const std::vector<int>& members = regions.members;

  // Pixel areas, cluster counts and seeds per region.
  std::vector<float> area(n_px, 0.0f);
  std::vector<int> K(static_cast<std::size_t>(num_regions), 0);
  std::vector<Cluster> clusters;
  std::vector<int> covered(n_px, -1);
  const detail::PixelArea pixel_area(k, min_cos);
  for (int r = 0; r < num_regions; ++r) {
    const int* first = members.data() + regions.start[r];
    const int n = regions.start[r + 1] - regions.start[r];
    if (n == 0) continue;
    double total_area = 0.0;
    for (int j = 0; j < n; ++j) {
      const int i = first[j];
      area[i] = pixel_area(point[i], normal[i]);
      total_area += area[i];
    }
    K[r] = std::max(1, static_cast<int>(std::lround(total_area / p.target_patch_area_m2)));
    if (K[r] > 1) seedRegion(r, first, n, K[r], region, point, normal, w, h, k, p, clusters, covered);
  }

  // ---- Lloyd iterations of all regions' clusters together (each pixel only ever compares the
  //      clusters of its own region): the first kmeans_coarse_iterations on every (2 step)-th
  //      pixel each way (the centres move most then), the rest on every step-th, then one
  //      assignment of every pixel to the converged centres.
  std::vector<float> best;
  std::vector<int> assign;
  if (!clusters.empty()) {
    const int step = std::max(1, p.kmeans.kmeans_iteration_step_px);
    const int iterations = std::max(1, p.kmeans.kmeans_iterations);
    const int coarse_iterations = std::clamp(p.kmeans.kmeans_coarse_iterations, 0, iterations);
    const Lattice all(1, w, h, region, point, normal, has_normal, area.data());
    std::optional<Lattice> fine, coarse;
    if (step > 1 && coarse_iterations < iterations) fine.emplace(step, w, h, region, point, normal, has_normal, area.data());
    if (coarse_iterations > 0) coarse.emplace(2 * step, w, h, region, point, normal, has_normal, area.data());
    for (int it = 0; it < iterations; ++it) {
      const Lattice& lattice = it < coarse_iterations ? *coarse : fine ? *fine : all;
      assignLattice(lattice, clusters, regions.boxes, k, radius, w_n, best, assign);
      updateCentres(lattice, assign, clusters);
    }
    assignLattice(all, clusters, regions.boxes, k, radius, w_n, best, assign);
  }

  // Patch ids region by region, within a region in raster order of first pixel.
  AreaPatches out;
  out.labels = cv::Mat(h, w, CV_32S, cv::Scalar(-1));
  int* L = out.labels.ptr<int>(0);
  std::vector<int> id(clusters.size(), -1);
  for (int r = 0; r < num_regions; ++r) {
    const int n = regions.start[r + 1] - regions.start[r];
    if (n == 0) continue;
    const int* first = members.data() + regions.start[r];
    if (K[r] == 1) {
      for (int j = 0; j < n; ++j) L[first[j]] = out.count;
      ++out.count;
      continue;
    }
    for (int j = 0; j < n; ++j) {
      const int i = first[j], c = assign[i];
      if (c < 0) continue;
      if (id[c] < 0) id[c] = out.count++;
      L[i] = id[c];
    }
  }
  return out;
}

}  // namespace gasp
