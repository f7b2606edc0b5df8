#include "full_resolution.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "contiguity.h"
#include "crease_borders.h"
#include "leftover_pixels.h"
#include "pixel_area.h"
#include "region_growing.h"
#include "step_borders.h"

namespace gasp::detail {

namespace {

/// The link rule of depth_links.h.
struct Linked {
  float abs_m, rel;
  bool operator()(float a, float b) const {
    const float lo = std::min(a, b);
    return std::abs(a - b) <= abs_m + rel * lo * lo;
  }
};

/// Plane models of the grid's patches from the cells the k-means placed (smooth surface; crease
/// and edge bands blend two surfaces in their normals and points), from all their cells where a
/// patch has none of those. Areas are not needed here.
std::vector<PlaneModel> gridModels(const int* GL, const std::vector<std::uint8_t>& core, int count,
                                   const Eigen::Vector3f* points, const Eigen::Vector3f* normals) {
  struct Sums {
    Eigen::Vector3d p = Eigen::Vector3d::Zero(), n = Eigen::Vector3d::Zero();
    int cells = 0;
  };
  std::vector<Sums> core_sums(static_cast<std::size_t>(count)), all_sums(static_cast<std::size_t>(count));
  for (std::size_t j = 0; j < core.size(); ++j) {
    const int l = GL[j];
    if (l < 0) continue;
    Sums& s = core[j] ? core_sums[static_cast<std::size_t>(l)] : all_sums[static_cast<std::size_t>(l)];
    s.p += points[j].cast<double>();
    s.n += normals[j].cast<double>();
    ++s.cells;
  }
  std::vector<PlaneModel> models(static_cast<std::size_t>(count));
  for (std::size_t c = 0; c < models.size(); ++c) {
    Sums s = core_sums[c];
    if (s.cells == 0) s = all_sums[c];  // the non-core cells were summed apart
    if (s.cells == 0) continue;
    models[c].centroid = (s.p / s.cells).cast<float>();
    models[c].normal = s.n.norm() > 0 ? s.n.normalized().cast<float>() : (-models[c].centroid).normalized();
  }
  return models;
}

/// The grid cells with a border of empty cells around, so that a cell's 3 x 3 neighbourhood lies
/// at fixed offsets: label (-1 = none), depth, the cell's index in the grid, k-means-placed (core)
/// and with-normal flags.
struct PaddedCells {
  int width = 0;
  std::vector<int> label, index;
  std::vector<float> z;
  std::vector<std::uint8_t> core, has_normal;
  int offsets[9] = {};

  PaddedCells(const int* GL, const std::vector<std::uint8_t>& core_cells, const int* radius,
              const Eigen::Vector3f* points, int cw, int ch)
      : width(cw + 2) {
    const std::size_t n = static_cast<std::size_t>(cw + 2) * (ch + 2);
    label.assign(n, -1), index.assign(n, -1), z.assign(n, 0.0f), core.assign(n, 0), has_normal.assign(n, 0);
    for (int r = 0; r < ch; ++r)
      for (int c = 0; c < cw; ++c) {
        const int j = r * cw + c;
        const std::size_t jp = static_cast<std::size_t>(r + 1) * width + c + 1;
        label[jp] = GL[j], index[jp] = j, z[jp] = points[j].z(), core[jp] = core_cells[static_cast<std::size_t>(j)];
        has_normal[jp] = radius[j] > 0;
      }
    int k = 0;
    for (int dr = -1; dr <= 1; ++dr)
      for (int dc = -1; dc <= 1; ++dc) offsets[k++] = dr * width + dc;
  }
  int at(int r, int c) const { return (r + 1) * width + c + 1; }

  /// The cell's label is the only one in its 3 x 3 neighbourhood (empty cells aside).
  bool uniform(int jp) const {
    const int l0 = label[static_cast<std::size_t>(jp)];
    bool same = l0 >= 0;
    for (const int o : offsets) {
      const int l = label[static_cast<std::size_t>(jp + o)];
      same &= l == l0 || l < 0;
    }
    return same;
  }
};

/// The patches of a cell's 3 x 3 neighbourhood, each with the depth range of its cells there, the
/// normal of one of them (-1: none has one) and whether the k-means placed all of them. A pixel
/// is on a candidate's surface when its depth is linked to that range.
struct Candidate {
  int label;
  float z_lo, z_hi;
  int normal_cell;
  bool core;
};

/// Labels every pixel (-1 where invalid or on no surface around) and writes which cell's normal it
/// takes (-1: none): its own cell's when on its surface, else the first candidate's on its surface.
///  - Only one patch in the cell's 3 x 3 neighbourhood (most cells), or only its patch in the four
///    cells nearest to the pixel when the k-means placed the cell: the pixels on the cell's surface
///    take it.
///  - Else, among the patches of the 3 x 3 cells on the pixel's surface: by the k-means distance
///    when the k-means placed all their cells here (a border within a smooth surface); by the
///    clean-up's growth cost, distance to the patch plane plus normal mismatch, when cells set
///    aside on the grid are involved (creases, depth edges: the clean-up grew those as whole
///    cells, and a cell across a crease could take only one label).
/// Counts the pixels of each patch; appends the valid pixels left unlabelled to `unlabelled`.
void upsample(const int* GL, const std::vector<PlaneModel>& models, const CoarseGrid& g, const SurfaceNormals& gn,
              const std::vector<std::uint8_t>& core, const OrganizedPointCloud& cloud, const DepthLinks& links,
              const SuperpixelParams& p, int* L, int* N, int* pixel_counts,
              std::vector<int>& unlabelled) {
  const int s = g.step, w = cloud.width, h = cloud.height, cw = g.cloud.width, ch = g.cloud.height;
  const int* GR = gn.radius.ptr<int>(0);
  const auto* GN = reinterpret_cast<const Eigen::Vector3f*>(gn.normals.ptr<float>(0));
  const auto* GS = reinterpret_cast<const Eigen::Vector3f*>(gn.smoothed.ptr<float>(0));
  const PaddedCells cells(GL, core, GR, g.cloud.points.data(), cw, ch);
  const Linked linked{static_cast<float>(p.surfaces.discontinuity_abs_m), static_cast<float>(p.surfaces.discontinuity_rel)};
  const float radius = static_cast<float>(std::sqrt(p.target_patch_area_m2 / M_PI));
  const float inv_r2 = 1.0f / (radius * radius), w_km = static_cast<float>(p.kmeans.kmeans_normal_weight);
  const float w_grow = static_cast<float>(p.cleanup.regrow_normal_weight_m);
  const Eigen::Vector3f zero = Eigen::Vector3f::Zero();
  // Offset (-1, 0, +1) of the neighbouring cell on the side of a pixel's position within its cell
  // (0 at the middle of odd steps).
  std::vector<int> side(static_cast<std::size_t>(s));
  for (int d = 0; d < s; ++d) side[d] = 2 * d < s - 1 ? -1 : 2 * d > s - 1 ? 1 : 0;

  Candidate around[9];
  int n_around = 0;
  auto gather = [&](int jp) {
    n_around = 0;
    for (const int o : cells.offsets) {
      const std::size_t j = static_cast<std::size_t>(jp + o);
      const int l = cells.label[j];
      if (l < 0) continue;
      const float zj = cells.z[j];
      const int nj = cells.has_normal[j] ? cells.index[j] : -1;
      int k = 0;
      while (k < n_around && around[k].label != l) ++k;
      if (k == n_around) {
        around[n_around++] = {l, zj, zj, nj, cells.core[j] != 0};
        continue;
      }
      Candidate& a = around[k];
      a.z_lo = std::min(a.z_lo, zj), a.z_hi = std::max(a.z_hi, zj);
      if (a.normal_cell < 0) a.normal_cell = nj;
      a.core = a.core && cells.core[j];
    }
  };

  // A pixel at a border: returns its label and sets its normal's cell. Branch-light (the gates are
  // data-dependent and mispredict): every candidate is gated and costed, the minimum selected.
  auto decide = [&](int i, int own, bool own_on, int& normal) {
    const Eigen::Vector3f q = cloud.points[static_cast<std::size_t>(i)];
    const float z = q.z();
    int normal_cell = own_on && GR[own] > 0 ? own : -1;
    bool on[9], all_core = true;
    int n_on = 0;
    for (int k = 0; k < n_around; ++k) {
      const Candidate& c = around[k];
      on[k] = ((z >= c.z_lo) & (z <= c.z_hi)) | linked(z, c.z_lo) | linked(z, c.z_hi);
      n_on += on[k];
      all_core &= !on[k] | c.core;
      normal_cell = normal_cell < 0 && on[k] ? c.normal_cell : normal_cell;
    }
    const bool has_normal = normal_cell >= 0;
    const Eigen::Vector3f n = has_normal ? GN[normal_cell] : zero;
    normal = normal_cell;
    if (n_on == 0) return -1;
    if (n_on == 1)  // one patch around on the pixel's surface (depth edges, mostly)
      for (int k = 0; k < n_around; ++k)
        if (on[k]) return around[k].label;
    int label = -1;
    float best = std::numeric_limits<float>::infinity();
    if (all_core) {
      // The k-means distance, on the pixel's ray at the depth averaged over its cell's normal
      // window (raw depth noise would fray the borders, as it would the k-means cells).
      const Eigen::Vector3f qs = own_on && GR[own] > 0 ? Eigen::Vector3f(q * (GS[own].z() / z)) : q;
      for (int k = 0; k < n_around; ++k) {
        const PlaneModel& m = models[static_cast<std::size_t>(around[k].label)];
        const float d = on[k] ? (qs - m.centroid).squaredNorm() * inv_r2 - w_km * n.dot(m.normal)
                              : std::numeric_limits<float>::infinity();
        label = d < best ? around[k].label : label;
        best = d < best ? d : best;
      }
      return label;
    }
    const float w_n = has_normal ? w_grow : 0.0f;
    for (int k = 0; k < n_around; ++k) {
      const PlaneModel& m = models[static_cast<std::size_t>(around[k].label)];
      const float d = on[k] ? std::abs(m.normal.dot(q - m.centroid)) + w_n * (1.0f - std::abs(m.normal.dot(n)))
                            : std::numeric_limits<float>::infinity();
      label = d < best ? around[k].label : label;
      best = d < best ? d : best;
    }
    return label;
  };

  for (int cr = 0; cr < ch; ++cr) {
    const int v0 = s * cr, v1 = std::min(h, v0 + s);
    for (int cc = 0; cc < cw; ++cc) {
      const int own = cr * cw + cc, jp = cells.at(cr, cc), l0 = GL[own];
      const int u0 = s * cc, u1 = std::min(w, u0 + s);
      const bool uniform = cells.uniform(jp), own_core = core[static_cast<std::size_t>(own)] != 0;
      const float zc = cells.z[static_cast<std::size_t>(jp)];
      const int nc = GR[own] > 0 ? own : -1;
      bool gathered = false;
      int own_count = 0;
      for (int v = v0; v < v1; ++v) {
        const int dv = side[static_cast<std::size_t>(v - v0)] * cells.width;
        for (int u = u0; u < u1; ++u) {
          const int i = v * w + u;
          if (!(links.bits(i) & DepthLinks::kValid)) {
            L[i] = -1;
            N[i] = -1;
            continue;
          }
          const bool own_on = l0 >= 0 && linked(cloud.points[static_cast<std::size_t>(i)].z(), zc);
          bool fast = own_on && uniform;
          if (own_on && !uniform && own_core) {  // the four nearest cells
            const int du = side[static_cast<std::size_t>(u - u0)];
            const int a = cells.label[static_cast<std::size_t>(jp + du)], b = cells.label[static_cast<std::size_t>(jp + dv)],
                      c = cells.label[static_cast<std::size_t>(jp + du + dv)];
            fast = (a == l0 || a < 0) && (b == l0 || b < 0) && (c == l0 || c < 0);
          }
          if (fast) {
            L[i] = l0;
            N[i] = nc;
            ++own_count;
            continue;
          }
          if (!gathered) gather(jp), gathered = true;
          int n = -1;
          const int l = decide(i, own, own_on, n);
          L[i] = l;
          N[i] = n;
          if (l >= 0) ++pixel_counts[l];
          else unlabelled.push_back(i);
        }
      }
      if (own_count > 0) pixel_counts[l0] += own_count;
    }
  }
}

}  // namespace

FullResolutionLabels refineToFullResolution(const cv::Mat& grid_labels, int grid_count, const CoarseGrid& g,
                                            const SurfaceNormals& gn, const OrganizedPointCloud& cloud,
                                            const DepthLinks& links, const CameraIntrinsics& k,
                                            const SuperpixelParams& p) {
  const float min_cos = static_cast<float>(std::cos(p.max_incidence_deg * M_PI / 180.0));
  FullResolutionLabels out;
  out.labels = cv::Mat(cloud.height, cloud.width, CV_32S);    // every pixel written by upsample()
  out.normal_cell.resize(static_cast<std::size_t>(cloud.width) * cloud.height);  // likewise
  int* L = out.labels.ptr<int>(0);
  int* N = out.normal_cell.data();
  const PixelNormals normals{reinterpret_cast<const Eigen::Vector3f*>(gn.normals.ptr<float>(0)), N};
  const std::size_t n_cells = grid_labels.total();
  const int* GL = grid_labels.ptr<int>(0);
  const int* GR = gn.radius.ptr<int>(0);
  const float* GC = gn.crease.ptr<float>(0);
  const float max_crease = static_cast<float>(p.surfaces.max_crease_angle_deg * M_PI / 180.0);
  std::vector<std::uint8_t> core(n_cells);
  for (std::size_t j = 0; j < n_cells; ++j) core[j] = GR[j] > 0 && GC[j] <= max_crease;
  std::vector<PlaneModel> models = gridModels(GL, core, grid_count, g.cloud.points.data(),
                                              reinterpret_cast<const Eigen::Vector3f*>(gn.normals.ptr<float>(0)));
  std::vector<int> counts(static_cast<std::size_t>(grid_count), 0), unlabelled;
  upsample(GL, models, g, gn, core, cloud, links, p, L, N, counts.data(), unlabelled);
  // Borders along creases follow the planes' intersection (crease_borders.h).
  if (p.borders.crease_borders) {
    SurfacePlanes planes = findSurfacePlanes(L, grid_count, models, counts.data(), links, p);
    refineCreaseBorders(L, grid_count, planes, models, counts.data(), N, cloud, links, k, p);
    if (p.borders.step_borders) refineStepBorders(L, grid_count, std::move(planes), models, counts.data(), N, cloud, links, p);
  }
  // Each patch keeps its largest linked piece; pixels cut off (and those on no surface around)
  // join adjacent patches within two patch radii of their plane, as in the clean-up's second
  // pass. There are few, so the patches' area is not limited.
  keepLargestPieces(out.labels, links, counts.data(), &unlabelled);
  for (std::size_t c = 0; c < models.size(); ++c) models[c].pixels = counts[c];
  const float radius = static_cast<float>(std::sqrt(p.target_patch_area_m2 / M_PI));
  const GrowthLimits limits{2.0f * radius, std::numeric_limits<float>::infinity(),
                            static_cast<float>(p.cleanup.regrow_normal_weight_m)};
  growPatches(L, links, cloud.points.data(), normals, models, limits, k, min_cos, &unlabelled);
  settleLeftoverPixels(L, grid_count, models, cloud, links, normals, k, p, min_cos, unlabelled);
  out.count = static_cast<int>(models.size());
  // Area factors: pixel_area.h for the point z * ray, with the ray of the cell's centre.
  const PixelArea pixel_area(k, min_cos);
  const auto* GN = reinterpret_cast<const Eigen::Vector3f*>(gn.normals.ptr<float>(0));
  out.cell_area_factor.assign(n_cells, 0.0f);
  for (int r = 0; r < g.cloud.height; ++r)
    for (int c = 0; c < g.cloud.width; ++c) {
      const std::size_t j = static_cast<std::size_t>(r) * g.cloud.width + c;
      if (GR[j] <= 0) continue;
      const Eigen::Vector3f ray(static_cast<float>((c - g.intrinsics.cx) / g.intrinsics.fx),
                                static_cast<float>((r - g.intrinsics.cy) / g.intrinsics.fy), 1.0f);
      out.cell_area_factor[j] = pixel_area(ray, GN[j]);  // z = 1
    }
  return out;
}

}  // namespace gasp::detail
