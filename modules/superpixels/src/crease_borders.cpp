#include "crease_borders.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace gasp::detail {

int refineCreaseBorders(int* L, int count, const SurfacePlanes& sp, const std::vector<PlaneModel>& models,
                        int* pixel_counts, int* normal_cell, const OrganizedPointCloud& cloud,
                        const DepthLinks& links, const CameraIntrinsics& k, const SuperpixelParams& p) {
  const std::size_t n_labels = static_cast<std::size_t>(count);
  const int n_px = cloud.width * cloud.height;
  if (sp.planes.size() < 2) return 0;
  const auto& adj = sp.adjacency;
  const auto& border = sp.border;
  const auto& planes = sp.planes;
  const auto& plane_of = sp.plane_of;
  const auto centroid = [&](int l) { return models[static_cast<std::size_t>(l)].centroid.cast<double>(); };
  const double cos_crease = std::cos(p.borders.crease_min_angle_deg * M_PI / 180.0);

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
    const double min_side = p.surfaces.discontinuity_abs_m;  // a patch right at the other plane tells no side
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
  for (int sweep = 0; sweep < p.borders.crease_band_px && !candidates.empty(); ++sweep) {
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
