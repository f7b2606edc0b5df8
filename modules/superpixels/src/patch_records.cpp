#include "patch_records.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <limits>

#include "gasp/superpixels/depth_superpixels.h"
#include "pixel_area.h"

namespace gasp {

namespace detail {

void recordPatches(SuperpixelSegmentation& seg, int label_bound, const OrganizedPointCloud& cloud,
                   const DepthLinks& links, const PixelNormals& normal_of, const ViewProjection& k,
                   const SuperpixelParams& p, bool relabel, const float* cell_area_factor) {
  const int w = cloud.width, h = cloud.height;
  const PixelArea pixel_area(k, static_cast<float>(std::cos(p.max_incidence_deg * M_PI / 180.0)));
  const std::size_t bound = static_cast<std::size_t>(label_bound);
  int* L = seg.labels.ptr<int>(0);
  const Eigen::Vector3f* P = cloud.points.data();
  // Per label as found in the image: moments of the points relative to the patch's first point
  // (no cancellation in the covariance) -- sums of points, of their products (upper triangle), of
  // normals -- accumulated per run of one label in a row, then added to the patch.
  struct Moments {
    Eigen::Vector3f origin = Eigen::Vector3f::Zero();
    double x = 0, y = 0, z = 0, xx = 0, xy = 0, xz = 0, yy = 0, yz = 0, zz = 0, nx = 0, ny = 0, nz = 0;
    double area = 0;  // of the pixels with a normal
    int pixels = 0;
    cv::Point lo{std::numeric_limits<int>::max(), std::numeric_limits<int>::max()}, hi{-1, -1};
  };
  std::vector<Moments> mo(bound);
  std::vector<int> id(bound, -1);  // final id per label, in raster order of first pixel
  int count = 0;
  // Neighbours per label as found; a border repeats the same pair pixel after pixel.
  std::vector<std::vector<int>> near(bound);
  int last_a = -1, last_b = -1;
  auto addEdge = [&](int a, int b) {
    if (a == last_a && b == last_b) return;
    last_a = a, last_b = b;
    auto& list = near[static_cast<std::size_t>(a)];
    if (std::find(list.begin(), list.end(), b) == list.end()) list.push_back(b);
  };
  std::vector<int> without_normal;
  for (int v = 0; v < h; ++v) {
    for (int u = 0; u < w;) {
      const int i0 = v * w + u, l = L[i0];
      if (l < 0) {
        ++u;
        continue;
      }
      Moments& m = mo[static_cast<std::size_t>(l)];
      if (id[l] < 0) id[l] = relabel ? count++ : l, m.origin = P[i0];
      float x = 0, y = 0, z = 0, xx = 0, xy = 0, xz = 0, yy = 0, yz = 0, zz = 0, nx = 0, ny = 0, nz = 0, area = 0;
      const int begin = u;
      for (; u < w && L[v * w + u] == l; ++u) {
        const int i = v * w + u;
        const Eigen::Vector3f& q = P[i];
        const float dx = q.x() - m.origin.x(), dy = q.y() - m.origin.y(), dz = q.z() - m.origin.z();
        x += dx, y += dy, z += dz;
        xx += dx * dx, xy += dx * dy, xz += dx * dz, yy += dy * dy, yz += dy * dz, zz += dz * dz;
        const Eigen::Vector3f pn = normal_of(i);
        if (pn.x() != 0.0f || pn.y() != 0.0f || pn.z() != 0.0f) {  // zero where the pixel has no normal
          nx += pn.x(), ny += pn.y(), nz += pn.z();
          area += cell_area_factor ? q.z() * q.z() * cell_area_factor[normal_of.cell[i]] : pixel_area(q, pn);
        } else {
          without_normal.push_back(i);
        }
        // The row below still holds the labels as found: pairs are of those, mapped at the end.
        if ((links.bits(i) & DepthLinks::kDown) && L[i + w] >= 0 && L[i + w] != l) addEdge(l, L[i + w]);
      }
      m.x += x, m.y += y, m.z += z, m.xx += xx, m.xy += xy, m.xz += xz, m.yy += yy, m.yz += yz, m.zz += zz;
      m.nx += nx, m.ny += ny, m.nz += nz, m.area += area;
      m.pixels += u - begin;
      m.lo.x = std::min(m.lo.x, begin), m.lo.y = std::min(m.lo.y, v);
      m.hi.x = std::max(m.hi.x, u - 1), m.hi.y = std::max(m.hi.y, v);
      const int last = v * w + u - 1;
      if (u < w && (links.bits(last) & DepthLinks::kRight) && L[last + 1] >= 0) addEdge(l, L[last + 1]);
      if (relabel) std::fill(L + v * w + begin, L + v * w + u, id[l]);
    }
  }
  if (!relabel) count = label_bound;
  seg.patches.assign(static_cast<std::size_t>(count), SurfacePatch{});
  for (std::size_t l = 0; l < bound; ++l) {
    if (id[l] < 0) continue;
    auto& patch = seg.patches[static_cast<std::size_t>(id[l])];
    const Moments& m = mo[l];
    patch.id = id[l];
    patch.pixel_count = m.pixels;
    const double c = m.pixels;
    const Eigen::Vector3d mean(m.x / c, m.y / c, m.z / c);  // relative to the origin
    patch.centroid = m.origin.cast<double>() + mean;
    Eigen::Matrix3d pp;
    pp << m.xx, m.xy, m.xz, m.xy, m.yy, m.yz, m.xz, m.yz, m.zz;
    patch.covariance = pp / c - mean * mean.transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(patch.covariance);
    const Eigen::Vector3d ev = eig.eigenvalues().cwiseMax(0.0);
    patch.planarity = ev(1) > 0 ? 1.0 - ev(0) / ev(1) : 0.0;
    const Eigen::Vector3d sum_n(m.nx, m.ny, m.nz);
    if (sum_n.norm() > 1e-9) {
      patch.normal = sum_n.normalized();
    } else {  // no pixel with a normal: the covariance's least direction, facing the camera
      patch.normal = eig.eigenvectors().col(0);
      if (patch.normal.dot(patch.centroid) > 0) patch.normal = -patch.normal;
    }
    patch.area_m2 = m.area;
    patch.bbox = cv::Rect(m.lo, m.hi + cv::Point(1, 1));
  }
  // Pixels without a normal are foreshortened by their patch's normal (labels are final here).
  for (const int i : without_normal) {
    auto& patch = seg.patches[static_cast<std::size_t>(L[i])];
    patch.area_m2 += pixel_area(P[i], patch.normal.cast<float>());
  }
  // Adjacency in final ids, both ways, sorted and without repeats.
  seg.adjacency.assign(static_cast<std::size_t>(count), {});
  for (std::size_t a = 0; a < bound; ++a)
    for (const int b : near[a]) {
      seg.adjacency[static_cast<std::size_t>(id[a])].push_back(id[b]);
      seg.adjacency[static_cast<std::size_t>(id[b])].push_back(id[a]);
    }
  for (auto& list : seg.adjacency) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
}

}  // namespace detail

void computePatchRecords(SuperpixelSegmentation& seg, int count, const OrganizedPointCloud& cloud,
                         const DepthLinks& links, const cv::Mat& normals, const ViewProjection& k,
                         const SuperpixelParams& p) {
  const detail::PixelNormals normal_of{reinterpret_cast<const Eigen::Vector3f*>(normals.ptr<float>(0))};
  detail::recordPatches(seg, count, cloud, links, normal_of, k, p, false);
}

}  // namespace gasp
