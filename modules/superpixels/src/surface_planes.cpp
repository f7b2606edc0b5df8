#include "surface_planes.h"

#include <algorithm>
#include <cmath>

#include "disjoint_sets.h"

namespace gasp::detail {

namespace {

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

SurfacePlanes findSurfacePlanes(const int* L, int count, const std::vector<PlaneModel>& models,
                                const int* pixel_counts, const DepthLinks& links, const SuperpixelParams& p) {
  const std::size_t n_labels = static_cast<std::size_t>(count);
  SurfacePlanes out;
  out.border.assign(static_cast<std::size_t>(links.width()) * links.height(), 0);
  out.adjacency = adjacency(L, count, links, out.border);
  const auto& adj = out.adjacency;
  const auto known = [&](int l) {
    return pixel_counts[l] > 0 && models[static_cast<std::size_t>(l)].normal.squaredNorm() > 0.5f;
  };
  const auto normal = [&](int l) { return models[static_cast<std::size_t>(l)].normal.cast<double>(); };
  const auto centroid = [&](int l) { return models[static_cast<std::size_t>(l)].centroid.cast<double>(); };
  const auto tolerance = [&](double z) { return p.borders.plane_noise_abs_m + p.borders.plane_noise_rel * z * z; };
  const double cos_same = std::cos(p.surfaces.max_neighbour_normal_angle_deg * M_PI / 180.0);

  // 1. Interior patches, grouped into planar surfaces.
  auto& interior = out.interior;
  interior.assign(n_labels, 0);
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
  auto& planes = out.planes;
  std::vector<int> plane_of_root(n_labels, -1);
  for (std::size_t r = 0; r < n_labels; ++r) {
    const SurfacePlane& sp = group_planes[r];
    if (sp.normal.isZero()) continue;  // not a group of >= 3 patches
    if (std::sqrt(square_sums[r] / sums[r].weight) > tolerance(sp.point.z())) continue;
    plane_of_root[r] = static_cast<int>(planes.size());
    planes.push_back(sp);
  }
  auto& plane_of = out.plane_of;
  plane_of.assign(n_labels, -1);
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

  return out;
}

}  // namespace gasp::detail
