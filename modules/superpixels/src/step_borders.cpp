#include "step_borders.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <utility>

#include <opencv2/imgproc/detail/gcgraph.hpp>

#include "gasp/core/median.h"

namespace gasp::detail {

namespace {

/// Half-width of the band cut along a step border [px]: the earlier stages leave such borders
/// 2-5 px off at 4 m (patches of ~9 x 9 px).
constexpr int kStepBandPx = 4;

/// A patch with no plane in a component touching two parallel planes joins their cut when it is
/// adjacent to a patch of either plane or when its hops from the two planes through the
/// component add up to at most this (a bridge up to 3 patches wide): a step blurs the normals
/// about a normal window to either side. Farther patches with no plane (clutter on a desk) are no
/// step's blur and only made the cut large: on fr1_xyz, 57k of the 60k pixels cut per frame
/// before this limit (docs/superpixels.md).
constexpr int kMaxBridgeHops = 4;
constexpr int kFar = 1 << 20;

/// Median and robust standard deviation (1.4826 MAD) of a sample.
struct Spread {
  double median = 0.0, sigma = 0.0;
};
Spread robustSpread(std::vector<double> v) {
  Spread s;
  s.median = median(v);
  for (double& x : v) x = std::abs(x - s.median);
  s.sigma = 1.4826 * median(std::move(v));
  return s;
}

/// Robust standard deviation (1.4826 MAD) of the member patches' centroid offsets from their
/// plane, per plane: how well the plane is known at the scale of a patch.
std::vector<double> planeScatter(int count, const SurfacePlanes& sp, const std::vector<PlaneModel>& models) {
  std::vector<std::vector<double>> offsets(sp.planes.size());
  for (int l = 0; l < count; ++l) {
    const int q = sp.plane_of[static_cast<std::size_t>(l)];
    if (q < 0 || !sp.interior[static_cast<std::size_t>(l)]) continue;
    const SurfacePlane& plane = sp.planes[static_cast<std::size_t>(q)];
    offsets[static_cast<std::size_t>(q)].push_back(
        plane.normal.dot(models[static_cast<std::size_t>(l)].centroid.cast<double>()) - plane.offset);
  }
  std::vector<double> scatter(sp.planes.size(), 0.0);
  for (std::size_t q = 0; q < offsets.size(); ++q) scatter[q] = robustSpread(std::move(offsets[q])).sigma;
  return scatter;
}

/// Levels inside a surface plane: connected runs of at least 3 of its interior patches whose
/// centroids lie off it, on one side, by more than step_min_sigmas robust standard deviations of
/// its members' offsets (and at least discontinuity_abs_m). Each becomes a plane of its own,
/// parallel to the surface at the run's median offset (added to sp.planes, its patches' plane_of).
void splitLevels(int count, const std::vector<PlaneModel>& models, const SuperpixelParams& p, SurfacePlanes& sp) {
  auto& planes = sp.planes;
  auto& plane_of = sp.plane_of;
  const std::size_t n_surfaces = planes.size();
  std::vector<std::vector<int>> members(n_surfaces);
  for (int l = 0; l < count; ++l) {
    const int q = plane_of[static_cast<std::size_t>(l)];
    if (q >= 0 && sp.interior[static_cast<std::size_t>(l)]) members[static_cast<std::size_t>(q)].push_back(l);
  }
  std::vector<double> offset_of(static_cast<std::size_t>(count), 0.0);
  std::vector<std::int8_t> side(static_cast<std::size_t>(count), 0);
  std::vector<std::uint8_t> done(static_cast<std::size_t>(count), 0);
  for (std::size_t q = 0; q < n_surfaces; ++q) {
    const auto& list = members[q];
    const SurfacePlane surface = planes[q];
    std::vector<double> d;
    for (int l : list) {
      const double o = surface.normal.dot(models[static_cast<std::size_t>(l)].centroid.cast<double>()) - surface.offset;
      offset_of[static_cast<std::size_t>(l)] = o;
      d.push_back(o);
    }
    const Spread spread = robustSpread(std::move(d));
    const double m = spread.median;
    const double limit = std::max(p.borders.step_min_sigmas * spread.sigma, p.surfaces.discontinuity_abs_m);
    for (int l : list) {
      const double o = offset_of[static_cast<std::size_t>(l)] - m;
      side[static_cast<std::size_t>(l)] = o > limit ? 1 : (o < -limit ? -1 : 0);
    }
    for (int seed : list) {
      if (!side[static_cast<std::size_t>(seed)] || done[static_cast<std::size_t>(seed)]) continue;
      std::vector<int> run, stack{seed};
      done[static_cast<std::size_t>(seed)] = 1;
      while (!stack.empty()) {
        const int a = stack.back();
        stack.pop_back();
        run.push_back(a);
        for (int b : sp.adjacency[static_cast<std::size_t>(a)])
          if (!done[static_cast<std::size_t>(b)] && side[static_cast<std::size_t>(b)] == side[static_cast<std::size_t>(seed)] &&
              plane_of[static_cast<std::size_t>(b)] == static_cast<int>(q))
            done[static_cast<std::size_t>(b)] = 1, stack.push_back(b);
      }
      if (run.size() < 3) continue;
      std::vector<double> offsets;
      for (int l : run) offsets.push_back(offset_of[static_cast<std::size_t>(l)]);
      SurfacePlane level = surface;
      level.offset += median(offsets);
      level.point += (level.offset - surface.offset) * level.normal;
      for (int l : run) plane_of[static_cast<std::size_t>(l)] = static_cast<int>(planes.size());
      planes.push_back(level);
    }
  }
}

/// The patches around the border of two parallel surface planes a and b (a < b): patches of either
/// plane touching the other's; patches with no plane (their normals are blurred by the step),
/// connected through each other to both planes, next to either plane or in a bridge between them
/// (kMaxBridgeHops), and lying on one of them (within plane_noise);
/// and the patches of either plane touching those.
std::map<std::pair<int, int>, std::vector<int>> stepRegions(int count, const SurfacePlanes& sp,
                                                            const std::vector<PlaneModel>& models,
                                                            const int* pixel_counts, const SuperpixelParams& p) {
  const double cos_same = std::cos(p.surfaces.max_neighbour_normal_angle_deg * M_PI / 180.0);
  const auto parallel = [&](int a, int b) {
    return sp.planes[static_cast<std::size_t>(a)].normal.dot(sp.planes[static_cast<std::size_t>(b)].normal) >= cos_same;
  };
  const auto planeOf = [&](int l) { return sp.plane_of[static_cast<std::size_t>(l)]; };
  std::map<std::pair<int, int>, std::vector<int>> regions;
  // Direct contacts.
  for (int l = 0; l < count; ++l) {
    const int q = planeOf(l);
    if (q < 0) continue;
    for (int m : sp.adjacency[static_cast<std::size_t>(l)]) {
      const int r = planeOf(m);
      if (r >= 0 && r != q && parallel(q, r)) regions[{std::min(q, r), std::max(q, r)}].push_back(l);
    }
  }
  // Components of patches with no plane, and the planes each touches.
  std::vector<int> comp(static_cast<std::size_t>(count), -1);
  std::vector<std::vector<int>> comps, touched;
  for (int seed = 0; seed < count; ++seed) {
    if (planeOf(seed) >= 0 || pixel_counts[seed] <= 0 || comp[static_cast<std::size_t>(seed)] >= 0) continue;
    const int c = static_cast<int>(comps.size());
    comps.emplace_back();
    touched.emplace_back();
    std::vector<int> stack{seed};
    comp[static_cast<std::size_t>(seed)] = c;
    while (!stack.empty()) {
      const int a = stack.back();
      stack.pop_back();
      comps.back().push_back(a);
      for (int b : sp.adjacency[static_cast<std::size_t>(a)]) {
        const int r = planeOf(b);
        if (r >= 0) {
          auto& t = touched.back();
          if (std::find(t.begin(), t.end(), r) == t.end()) t.push_back(r);
        } else if (comp[static_cast<std::size_t>(b)] < 0 && pixel_counts[b] > 0) {
          comp[static_cast<std::size_t>(b)] = c;
          stack.push_back(b);
        }
      }
    }
    std::sort(touched.back().begin(), touched.back().end());
  }
  const auto onPlane = [&](int l, int q) {
    const SurfacePlane& plane = sp.planes[static_cast<std::size_t>(q)];
    const Eigen::Vector3d c = models[static_cast<std::size_t>(l)].centroid.cast<double>();
    return std::abs(plane.normal.dot(c) - plane.offset) <= p.borders.plane_noise_abs_m + p.borders.plane_noise_rel * c.z() * c.z();
  };
  // Hops from a plane's patches to the patches of component c, through the component (1:
  // adjacent to a patch of the plane), in `hops` (per label; reset by the caller).
  std::vector<int> hops_a(static_cast<std::size_t>(count), kFar), hops_b(hops_a), frontier;
  const auto hopsFrom = [&](int q, std::size_t c, std::vector<int>& hops) {
    frontier.clear();
    for (int l : comps[c])
      for (int m : sp.adjacency[static_cast<std::size_t>(l)])
        if (planeOf(m) == q) {
          hops[static_cast<std::size_t>(l)] = 1;
          frontier.push_back(l);
          break;
        }
    for (std::size_t f = 0; f < frontier.size(); ++f) {
      const int a = frontier[f];
      for (int b : sp.adjacency[static_cast<std::size_t>(a)])
        if (comp[static_cast<std::size_t>(b)] == static_cast<int>(c) && hops[static_cast<std::size_t>(b)] == kFar) {
          hops[static_cast<std::size_t>(b)] = hops[static_cast<std::size_t>(a)] + 1;
          frontier.push_back(b);
        }
    }
  };
  for (std::size_t c = 0; c < comps.size(); ++c) {
    const auto& t = touched[c];
    for (std::size_t i = 0; i < t.size(); ++i)
      for (std::size_t j = i + 1; j < t.size(); ++j) {
        if (!parallel(t[i], t[j])) continue;
        auto& region = regions[{t[i], t[j]}];
        hopsFrom(t[i], c, hops_a);
        hopsFrom(t[j], c, hops_b);
        for (int l : comps[c]) {
          const std::size_t lu = static_cast<std::size_t>(l);
          const bool bridge = std::min(hops_a[lu], hops_b[lu]) == 1 || hops_a[lu] + hops_b[lu] <= kMaxBridgeHops;
          hops_a[lu] = hops_b[lu] = kFar;
          if (!bridge || (!onPlane(l, t[i]) && !onPlane(l, t[j]))) continue;
          region.push_back(l);
          for (int m : sp.adjacency[lu])
            if (planeOf(m) == t[i] || planeOf(m) == t[j]) region.push_back(m);
        }
      }
  }
  for (auto& [key, region] : regions) {
    std::sort(region.begin(), region.end());
    region.erase(std::unique(region.begin(), region.end()), region.end());
  }
  return regions;
}

}  // namespace

int refineStepBorders(int* L, int count, SurfacePlanes sp, const std::vector<PlaneModel>& models,
                      int* pixel_counts, int* normal_cell, const OrganizedPointCloud& cloud,
                      const DepthLinks& links, const SuperpixelParams& p) {
  if (sp.planes.empty()) return 0;
  splitLevels(count, models, p, sp);
  if (sp.planes.size() < 2) return 0;
  const auto regions = stepRegions(count, sp, models, pixel_counts, p);
  if (regions.empty()) return 0;
  const auto scatter = planeScatter(count, sp, models);
  const int n_px = cloud.width * cloud.height;
  std::vector<int> slot(static_cast<std::size_t>(count), -1);  // a region patch's index
  std::vector<int> node(static_cast<std::size_t>(n_px), -1);   // a region pixel's graph vertex
  std::vector<int> pixels;
  std::vector<std::int8_t> side_of;  // per patch of the region: 0 = plane a, 1 = plane b, -1 = none yet
  // Which borders are steps: the planes' depth difference along the rays of the region's patch
  // centroids (median) is significant against how well the planes are known, and smaller than a
  // depth discontinuity there (larger steps were cut by the earlier stages).
  std::vector<const std::pair<const std::pair<int, int>, std::vector<int>>*> steps;
  std::vector<std::uint8_t> wanted(static_cast<std::size_t>(count), 0);
  for (const auto& entry : regions) {
    const auto& [key, region] = entry;
    const SurfacePlane& pa = sp.planes[static_cast<std::size_t>(key.first)];
    const SurfacePlane& pb = sp.planes[static_cast<std::size_t>(key.second)];
    std::vector<double> gaps, depths;
    for (int l : region) {
      const Eigen::Vector3d c = models[static_cast<std::size_t>(l)].centroid.cast<double>();
      const Eigen::Vector3d ray = c / c.z();
      gaps.push_back(pa.offset / pa.normal.dot(ray) - pb.offset / pb.normal.dot(ray));
      depths.push_back(c.z());
    }
    const double step = std::abs(median(gaps)), z = median(depths);
    const double min_step = std::max(p.surfaces.discontinuity_abs_m,
                                     p.borders.step_min_sigmas * std::hypot(scatter[static_cast<std::size_t>(key.first)],
                                                                    scatter[static_cast<std::size_t>(key.second)]));
    if (!(step >= min_step && step <= p.surfaces.discontinuity_abs_m + p.surfaces.discontinuity_rel * z * z)) continue;
    steps.push_back(&entry);
    for (int l : region) wanted[static_cast<std::size_t>(l)] = 1;
  }
  if (steps.empty()) return 0;
  // The pixels of those regions' patches, per patch (one pass over the image).
  std::vector<int> first(static_cast<std::size_t>(count) + 1, 0), listed;
  for (int i = 0; i < n_px; ++i)
    if (L[i] >= 0 && wanted[static_cast<std::size_t>(L[i])]) ++first[static_cast<std::size_t>(L[i]) + 1];
  for (std::size_t l = 0; l < static_cast<std::size_t>(count); ++l) first[l + 1] += first[l];
  listed.resize(static_cast<std::size_t>(first.back()));
  {
    std::vector<int> fill(first.begin(), first.end() - 1);
    for (int i = 0; i < n_px; ++i)
      if (L[i] >= 0 && wanted[static_cast<std::size_t>(L[i])]) listed[static_cast<std::size_t>(fill[static_cast<std::size_t>(L[i])]++)] = i;
  }
  int moved = 0;
  for (const auto* entry : steps) {
    const auto& [key, region] = *entry;
    const SurfacePlane& pa = sp.planes[static_cast<std::size_t>(key.first)];
    const SurfacePlane& pb = sp.planes[static_cast<std::size_t>(key.second)];
    for (std::size_t s = 0; s < region.size(); ++s) slot[static_cast<std::size_t>(region[s])] = static_cast<int>(s);
    const auto planes = key;  // a structured binding cannot be captured before C++20 (clang 14)
    const auto sideOfPlane = [&](int l) -> std::int8_t {  // by the patch's plane
      const int q = sp.plane_of[static_cast<std::size_t>(l)];
      return q == planes.first ? 0 : (q == planes.second ? 1 : -1);
    };
    side_of.resize(region.size());
    for (std::size_t s = 0; s < region.size(); ++s) side_of[s] = sideOfPlane(region[s]);
    // Residuals of the region's pixels to both planes, along their rays (depth differences).
    pixels.clear();
    std::vector<double> ra, rb, own;
    for (int l : region)
      for (int t = first[static_cast<std::size_t>(l)]; t < first[static_cast<std::size_t>(l) + 1]; ++t) {
        const int i = listed[static_cast<std::size_t>(t)];
        if (L[i] < 0 || slot[static_cast<std::size_t>(L[i])] < 0) continue;  // moved by an earlier step
        const Eigen::Vector3d x = cloud.points[static_cast<std::size_t>(i)].cast<double>();
        const Eigen::Vector3d ray = x / x.z();
        node[static_cast<std::size_t>(i)] = static_cast<int>(pixels.size());
        pixels.push_back(i);
        ra.push_back(x.z() - pa.offset / pa.normal.dot(ray));
        rb.push_back(x.z() - pb.offset / pb.normal.dot(ray));
        const int side = side_of[static_cast<std::size_t>(slot[static_cast<std::size_t>(L[i])])];
        if (side >= 0) own.push_back(std::abs(side == 0 ? ra.back() : rb.back()));
      }
    const double sigma = 1.4826 * median(own);  // pixel noise, from the pixels of either plane's patches
    // Only a band is cut: the pixels of patches with no plane and those up to kStepBandPx from
    // a border between patches of different sides; the rest pull to their patch's plane.
    {
      const auto sideAt = [&](int i) { return side_of[static_cast<std::size_t>(slot[static_cast<std::size_t>(L[i])])]; };
      std::vector<int> dist(pixels.size(), -1), frontier, next;
      for (std::size_t v = 0; v < pixels.size(); ++v) {
        const int i = pixels[v];
        bool seed = sideAt(i) < 0;
        if (!seed)
          links.forEachNeighbour(i, [&](int j) { seed |= node[static_cast<std::size_t>(j)] >= 0 && sideAt(j) != sideAt(i); });
        if (seed) dist[v] = 0, frontier.push_back(static_cast<int>(v));
      }
      for (int d = 1; d <= kStepBandPx && !frontier.empty(); ++d) {
        next.clear();
        for (int v : frontier)
          links.forEachNeighbour(pixels[static_cast<std::size_t>(v)], [&](int j) {
            const int vj = node[static_cast<std::size_t>(j)];
            if (vj >= 0 && dist[static_cast<std::size_t>(vj)] < 0) dist[static_cast<std::size_t>(vj)] = d, next.push_back(vj);
          });
        frontier.swap(next);
      }
      std::size_t kept = 0;
      for (std::size_t v = 0; v < pixels.size(); ++v) {
        if (dist[v] < 0) {
          node[static_cast<std::size_t>(pixels[v])] = -1;
          continue;
        }
        pixels[kept] = pixels[v], ra[kept] = ra[v], rb[kept] = rb[v];
        node[static_cast<std::size_t>(pixels[kept])] = static_cast<int>(kept);
        ++kept;
      }
      pixels.resize(kept), ra.resize(kept), rb.resize(kept);
    }
    // Empty when the region's pixels were all moved by an earlier step (no border left).
    if (sigma > 0.0 && !pixels.empty()) {
      // Minimum cut: source = plane a, sink = plane b (a pixel left on the sink side pays its
      // source weight).
      const double inv = 1.0 / (2.0 * sigma * sigma), cap = 4.5;  // truncated at 3 sigma
      cv::detail::GCGraph<double> graph(static_cast<unsigned>(pixels.size()), static_cast<unsigned>(4 * pixels.size()));
      for (std::size_t v = 0; v < pixels.size(); ++v) graph.addVtx();
      for (std::size_t v = 0; v < pixels.size(); ++v) {
        const int i = pixels[v];
        double cost_a = std::min(ra[v] * ra[v] * inv, cap), cost_b = std::min(rb[v] * rb[v] * inv, cap);
        links.forEachNeighbour(i, [&](int j) {
          const int vj = node[static_cast<std::size_t>(j)];
          if (vj >= 0) {
            if (j > i) graph.addEdges(static_cast<int>(v), vj, p.borders.step_smoothness, p.borders.step_smoothness);
            return;
          }
          if (L[j] < 0) return;  // a neighbour outside the band pulls to its plane
          const int side = sideOfPlane(L[j]);
          if (side == 0) cost_b += p.borders.step_smoothness;
          else if (side == 1) cost_a += p.borders.step_smoothness;
        });
        graph.addTermWeights(static_cast<int>(v), cost_b, cost_a);
      }
      graph.maxFlow();
      // Each patch without a plane takes the side most of its pixels are on.
      std::vector<int> votes(region.size(), 0);
      std::vector<std::int8_t> pixel_side(pixels.size());
      for (std::size_t v = 0; v < pixels.size(); ++v) {
        pixel_side[v] = graph.inSourceSegment(static_cast<int>(v)) ? 0 : 1;
        votes[static_cast<std::size_t>(slot[static_cast<std::size_t>(L[pixels[v]])])] += pixel_side[v] ? 1 : -1;
      }
      for (std::size_t s = 0; s < region.size(); ++s)
        if (side_of[s] < 0) side_of[s] = votes[s] > 0 ? 1 : 0;
      // Pixels on the other side of their patch's join a linked patch of their side, in sweeps.
      const auto sideOfPatch = [&](int l) -> int {
        if (l < 0) return -1;
        const int s = slot[static_cast<std::size_t>(l)];
        return s >= 0 ? side_of[static_cast<std::size_t>(s)] : sideOfPlane(l);
      };
      std::vector<std::size_t> pending;
      for (std::size_t v = 0; v < pixels.size(); ++v)
        if (sideOfPatch(L[pixels[v]]) != pixel_side[v]) pending.push_back(v);
      struct Move {
        std::size_t v;
        int label, via;
      };
      std::vector<Move> batch;
      for (int sweep = 0; sweep < 4 * p.borders.crease_band_px && !pending.empty(); ++sweep) {
        batch.clear();
        for (std::size_t v : pending) {
          const int i = pixels[v];
          int target = -1, via = -1;
          links.forEachNeighbour(i, [&](int j) {
            if (target >= 0 || L[j] < 0 || sideOfPatch(L[j]) != pixel_side[v]) return;
            const int vj = node[static_cast<std::size_t>(j)];
            if (vj >= 0 && sideOfPatch(L[j]) != pixel_side[static_cast<std::size_t>(vj)]) return;  // itself pending
            target = L[j], via = j;
          });
          if (target >= 0) batch.push_back({v, target, via});
        }
        if (batch.empty()) break;
        for (const Move& m : batch) {
          const int i = pixels[m.v];
          --pixel_counts[L[i]];
          ++pixel_counts[m.label];
          L[i] = m.label;
          normal_cell[i] = normal_cell[m.via];
        }
        moved += static_cast<int>(batch.size());
        pending.erase(std::remove_if(pending.begin(), pending.end(),
                                     [&](std::size_t v) { return sideOfPatch(L[pixels[v]]) == pixel_side[v]; }),
                      pending.end());
      }
    }
    for (int i : pixels) node[static_cast<std::size_t>(i)] = -1;
    for (int l : region) slot[static_cast<std::size_t>(l)] = -1;
  }
  return moved;
}

}  // namespace gasp::detail
