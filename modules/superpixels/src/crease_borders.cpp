#include "crease_borders.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "disjoint_sets.h"

namespace gasp::detail {

namespace {

struct SurfacePlane {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  ///< unit, facing the camera
  double offset = 0.0;                               ///< normal . point
};

/// Labels adjacent through a depth link, per label (a few each); border[i] = 1 for the pixels on
/// either side of such a link.
std::vector<std::vector<int>> adjacency(const int* L, int count, const DepthLinks& links,
                                        std::vector<std::uint8_t>& border) {
  std::vector<std::vector<int>> adj(static_cast<std::size_t>(count));
  const auto add = [&](int a, int b) {
    auto& list = adj[static_cast<std::size_t>(a)];
    if (std::find(list.begin(), list.end(), b) != list.end()) return;
    list.push_back(b);
    adj[static_cast<std::size_t>(b)].push_back(a);
  };
  const int w = links.width(), h = links.height();
  int right_a = -1, right_b = -1, down_a = -1, down_b = -1;  // a border repeats one pair
  for (int v = 0; v < h; ++v) {
    const int* row = L + static_cast<std::ptrdiff_t>(v) * w;
    const int* below = v + 1 < h ? row + w : nullptr;
    for (int u = 0; u < w; ++u) {
      const int a = row[u];
      if (a < 0) continue;
      const int i = v * w + u;
      const std::uint8_t bits = links.bits(i);
      if (bits & DepthLinks::kRight) {
        const int b = row[u + 1];
        if (b != a && b >= 0) {
          border[static_cast<std::size_t>(i)] = border[static_cast<std::size_t>(i) + 1] = 1;
          if (a != right_a || b != right_b) right_a = a, right_b = b, add(a, b);
        }
      }
      if (below && (bits & DepthLinks::kDown)) {
        const int b = below[u];
        if (b != a && b >= 0) {
          border[static_cast<std::size_t>(i)] = border[static_cast<std::size_t>(i + w)] = 1;
          if (a != down_a || b != down_b) down_a = a, down_b = b, add(a, b);
        }
      }
    }
  }
  for (auto& list : adj) std::sort(list.begin(), list.end());  // deterministic order
  return adj;
}

}  // namespace

int refineCreaseBorders(int* L, int count, const std::vector<PlaneModel>& models, int* pixel_counts,
                        int* normal_cell, const OrganizedPointCloud& cloud, const DepthLinks& links,
                        const CameraIntrinsics& k, const SuperpixelParams& p) {
  const std::size_t n_labels = static_cast<std::size_t>(count);
  const int n_px = cloud.width * cloud.height;
  std::vector<std::uint8_t> border(static_cast<std::size_t>(n_px), 0);
  const auto adj = adjacency(L, count, links, border);
  const auto known = [&](int l) {
    return pixel_counts[l] > 0 && models[static_cast<std::size_t>(l)].normal.squaredNorm() > 0.5f;
  };
  const auto normal = [&](int l) { return models[static_cast<std::size_t>(l)].normal.cast<double>(); };
  const auto centroid = [&](int l) { return models[static_cast<std::size_t>(l)].centroid.cast<double>(); };
  const auto tolerance = [&](double z) { return p.plane_noise_abs_m + p.plane_noise_rel * z * z; };
  const double cos_same = std::cos(p.max_neighbour_normal_angle_deg * M_PI / 180.0);
  const double cos_crease = std::cos(p.crease_min_angle_deg * M_PI / 180.0);

  // 1. Interior patches, grouped into planar surfaces.
  std::vector<std::uint8_t> interior(n_labels, 0);
  for (int l = 0; l < count; ++l) {
    const auto& list = adj[static_cast<std::size_t>(l)];
    if (!known(l) || list.empty()) continue;
    const Eigen::Vector3d n = normal(l);
    interior[static_cast<std::size_t>(l)] =
        std::all_of(list.begin(), list.end(), [&](int m) { return known(m) && n.dot(normal(m)) >= cos_same; });
  }
  const auto coplanar = [&](int a, int b) {
    const Eigen::Vector3d na = normal(a), nb = normal(b), ca = centroid(a), cb = centroid(b);
    if (na.dot(nb) < cos_same) return false;
    const double tol = 2.0 * tolerance(std::min(ca.z(), cb.z()));
    return std::abs(na.dot(cb - ca)) <= tol && std::abs(nb.dot(ca - cb)) <= tol;
  };
  DisjointSets sets(n_labels);
  for (int a = 0; a < count; ++a) {
    if (!interior[static_cast<std::size_t>(a)]) continue;
    for (int b : adj[static_cast<std::size_t>(a)])
      if (b > a && interior[static_cast<std::size_t>(b)] && coplanar(a, b)) sets.unite(a, b);
  }
  struct Sums {
    Eigen::Vector3d point = Eigen::Vector3d::Zero(), normal = Eigen::Vector3d::Zero();
    double weight = 0.0;
    int members = 0;
  };
  std::vector<Sums> sums(n_labels);
  for (int l = 0; l < count; ++l) {
    if (!interior[static_cast<std::size_t>(l)]) continue;
    Sums& s = sums[static_cast<std::size_t>(sets.find(l))];
    const double wl = pixel_counts[l];
    s.point += wl * centroid(l);
    s.normal += wl * normal(l);
    s.weight += wl;
    ++s.members;
  }
  std::vector<SurfacePlane> group_planes(n_labels);
  for (std::size_t r = 0; r < n_labels; ++r) {
    const Sums& s = sums[r];
    if (s.members < 3 || !(s.normal.norm() > 0.0)) continue;
    SurfacePlane& sp = group_planes[r];
    sp.point = s.point / s.weight;
    sp.normal = s.normal.normalized();
    sp.offset = sp.normal.dot(sp.point);
  }
  // Planar: the members' centroids lie on the plane (a chain over a curved surface does not).
  std::vector<double> square_sums(n_labels, 0.0);
  for (int l = 0; l < count; ++l) {
    if (!interior[static_cast<std::size_t>(l)]) continue;
    const auto r = static_cast<std::size_t>(sets.find(l));
    const double d = group_planes[r].normal.dot(centroid(l)) - group_planes[r].offset;
    square_sums[r] += pixel_counts[l] * d * d;
  }
  std::vector<SurfacePlane> planes;
  std::vector<int> plane_of_root(n_labels, -1);
  for (std::size_t r = 0; r < n_labels; ++r) {
    const SurfacePlane& sp = group_planes[r];
    if (sp.normal.isZero()) continue;  // not a group of >= 3 patches
    if (std::sqrt(square_sums[r] / sums[r].weight) > tolerance(sp.point.z())) continue;
    plane_of_root[r] = static_cast<int>(planes.size());
    planes.push_back(sp);
  }
  if (planes.size() < 2) return 0;
  std::vector<int> plane_of(n_labels, -1);
  for (int l = 0; l < count; ++l)
    if (interior[static_cast<std::size_t>(l)]) plane_of[static_cast<std::size_t>(l)] = plane_of_root[static_cast<std::size_t>(sets.find(l))];

  // 2. Patches along the crease take the plane of an adjacent group they lie on (the nearest).
  std::vector<int> border_plane(n_labels, -1);
  for (int l = 0; l < count; ++l) {
    if (plane_of[static_cast<std::size_t>(l)] >= 0 || !known(l)) continue;
    const Eigen::Vector3d c = centroid(l), n = normal(l);
    double best = tolerance(c.z());
    for (int m : adj[static_cast<std::size_t>(l)]) {
      const int q = plane_of[static_cast<std::size_t>(m)];
      if (q < 0) continue;
      const SurfacePlane& sp = planes[static_cast<std::size_t>(q)];
      const double d = std::abs(sp.normal.dot(c) - sp.offset);
      if (d <= best && n.dot(sp.normal) >= cos_same) best = d, border_plane[static_cast<std::size_t>(l)] = q;
    }
  }
  for (std::size_t l = 0; l < n_labels; ++l)
    if (border_plane[l] >= 0) plane_of[l] = border_plane[l];

  // 3. Border pixels, in sweeps.
  const auto atCrease = [&](int a, int b) {
    const int qa = plane_of[static_cast<std::size_t>(a)], qb = plane_of[static_cast<std::size_t>(b)];
    return qa >= 0 && qb >= 0 && qa != qb &&
           planes[static_cast<std::size_t>(qa)].normal.dot(planes[static_cast<std::size_t>(qb)].normal) <= cos_crease;
  };
  std::vector<std::uint8_t> active(n_labels, 0);
  for (int l = 0; l < count; ++l)
    for (int m : adj[static_cast<std::size_t>(l)])
      if (atCrease(l, m) || (plane_of[static_cast<std::size_t>(l)] < 0 && plane_of[static_cast<std::size_t>(m)] >= 0))
        active[static_cast<std::size_t>(l)] = 1;
  // +1 when the ray sees the surface of patch b rather than that of patch c (their planes meet
  // at a crease), -1 for c, 0 undecided. A patch lies on one side of the other's plane (its
  // centroid tells which); the surface a ray sees is the one whose hit lies on its own side.
  const auto sees = [&](const Eigen::Vector3d& ray, int b, int c) {
    if (!atCrease(b, c)) return 0;
    const SurfacePlane& pb = planes[static_cast<std::size_t>(plane_of[static_cast<std::size_t>(b)])];
    const SurfacePlane& pc = planes[static_cast<std::size_t>(plane_of[static_cast<std::size_t>(c)])];
    const double side_b = pc.normal.dot(centroid(b)) - pc.offset, side_c = pb.normal.dot(centroid(c)) - pb.offset;
    const double min_side = p.discontinuity_abs_m;  // a patch right at the other plane tells no side
    const double rb = pb.normal.dot(ray), rc = pc.normal.dot(ray);
    if (std::abs(side_b) < min_side || std::abs(side_c) < min_side || !(std::abs(rb) > 1e-9) || !(std::abs(rc) > 1e-9))
      return 0;
    const double tb = pb.offset / rb, tc = pc.offset / rc;  // ray parameters of the hits (= depths)
    if (!(tb > 0.0 && tc > 0.0)) return 0;
    const bool on_b = (side_b > 0.0) == (pc.normal.dot(tb * ray) - pc.offset > 0.0);
    const bool on_c = (side_c > 0.0) == (pb.normal.dot(tc * ray) - pb.offset > 0.0);
    return on_b == on_c ? 0 : (on_b ? 1 : -1);
  };
  const int w = cloud.width;
  const auto moves = [&](int i, int a, int b) {
    const int qb = plane_of[static_cast<std::size_t>(b)];
    if (qb < 0 || !active[static_cast<std::size_t>(a)]) return false;
    const Eigen::Vector3d ray((i % w - k.cx) / k.fx, (i / w - k.cy) / k.fy, 1.0);
    if (plane_of[static_cast<std::size_t>(a)] >= 0) {
      if (sees(ray, b, a) <= 0) return false;
    } else {  // a patch across the crease: b's surface must win against every crease neighbour's
      int wins = 0;
      for (int c : adj[static_cast<std::size_t>(a)]) {
        if (c == b || plane_of[static_cast<std::size_t>(c)] < 0) continue;
        const int s = sees(ray, b, c);
        if (s < 0) return false;
        wins += s;
      }
      if (wins == 0) return false;
    }
    const SurfacePlane& pb = planes[static_cast<std::size_t>(qb)];
    const float z_plane = static_cast<float>(pb.offset / pb.normal.dot(ray));
    return depthConnected(cloud.points[static_cast<std::size_t>(i)].z(), z_plane, p);
  };
  std::vector<int> candidates;
  for (int i = 0; i < n_px; ++i)
    if (border[static_cast<std::size_t>(i)] && active[static_cast<std::size_t>(L[i])]) candidates.push_back(i);
  struct Move {
    int pixel, label, via;
  };
  std::vector<Move> batch;
  std::vector<int> next;
  std::vector<std::uint8_t> queued(static_cast<std::size_t>(n_px), 0);
  int moved = 0;
  for (int sweep = 0; sweep < p.crease_band_px && !candidates.empty(); ++sweep) {
    batch.clear();
    for (int i : candidates) {  // decided on the labels of the sweep's start
      const int a = L[i];
      if (a < 0) continue;
      int target = -1, via = -1;
      links.forEachNeighbour(i, [&](int j) {
        if (target < 0 && L[j] >= 0 && L[j] != a && moves(i, a, L[j])) target = L[j], via = j;
      });
      if (target >= 0) batch.push_back({i, target, via});
    }
    next.clear();
    for (const Move& m : batch) {
      --pixel_counts[L[m.pixel]];
      ++pixel_counts[m.label];
      L[m.pixel] = m.label;
      normal_cell[m.pixel] = normal_cell[m.via];
      links.forEachNeighbour(m.pixel, [&](int j) {
        if (!queued[static_cast<std::size_t>(j)]) queued[static_cast<std::size_t>(j)] = 1, next.push_back(j);
      });
    }
    moved += static_cast<int>(batch.size());
    for (int j : next) queued[static_cast<std::size_t>(j)] = 0;
    std::sort(next.begin(), next.end());
    candidates.swap(next);
  }
  return moved;
}

}  // namespace gasp::detail
