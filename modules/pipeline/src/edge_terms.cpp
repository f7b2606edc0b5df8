#include "gasp/pipeline/edge_terms.h"

#include <nanoflann.hpp>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>

#include "gasp/core/depth_image.h"
#include "gasp/core/error.h"

namespace gasp {

namespace {

struct PointCloud3 {
  const std::vector<Eigen::Vector3d>* points = nullptr;
  std::size_t kdtree_get_point_count() const { return points->size(); }
  double kdtree_get_pt(std::size_t i, std::size_t d) const { return (*points)[i][static_cast<Eigen::Index>(d)]; }
  template <class BBox>
  bool kdtree_get_bbox(BBox&) const { return false; }
};
using EdgeTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, PointCloud3>, PointCloud3,
                                                     3, std::uint32_t>;

}  // namespace

void validate(const EdgeTermParams& p) {
  if (!(p.min_jump_m > 0) || !std::isfinite(p.min_jump_m) || !(p.jump_per_m2 >= 0) || !std::isfinite(p.jump_per_m2))
    throw Error("EdgeTermParams: min_jump_m must be > 0 and jump_per_m2 >= 0, both finite");
  if (p.pixel_step < 1) throw Error("EdgeTermParams: pixel_step must be >= 1");
  if (p.line_neighbours < 3) throw Error("EdgeTermParams: line_neighbours must be >= 3");
  if (!(p.max_distance_m > 0) || !std::isfinite(p.max_distance_m))
    throw Error("EdgeTermParams: max_distance_m must be finite and > 0");
  if (!(p.weight >= 0) || !std::isfinite(p.weight)) throw Error("EdgeTermParams: weight must be finite and >= 0");
}

namespace {

/// Edge pixels among those with (u + v) % 2 == 0. The edge condition marks a band two pixels wide
/// on the near side of a jump (neighbours 1 and 2 steps away), which holds pixels of both
/// parities whatever the edge's direction, so this checkerboard keeps about every other pixel
/// along any edge.
EdgePoints checkerboardEdgePixels(const DepthView& view, const EdgeTermParams& p) {
  EdgePoints e;
  const cv::Mat& d = view.depth_m;
  if (d.empty()) return e;
  if (d.type() != CV_32FC1) throw Error("edge terms: the view's depth must be CV_32FC1 [m]");
  const int w = d.cols, h = d.rows;
  const float inf = std::numeric_limits<float>::infinity();
  const std::ptrdiff_t stride = static_cast<std::ptrdiff_t>(d.step1());
  for (int v = 0; v < h; ++v) {
    const float* row = d.ptr<float>(v);
    const bool inner_row = v >= 2 && v + 2 < h;
    for (int u = v % 2; u < w; u += 2) {
      const float z = row[u];
      if (!isValidDepth(z)) continue;
      const float far = z + static_cast<float>(p.min_jump_m + p.jump_per_m2 * z * z);
      bool edge = false;
      if (inner_row && u >= 2 && u + 2 < w) {
        // Away from the image border: the eight neighbours without bounds checks, all evaluated
        // (a deeper valid neighbour: finite and beyond `far`, which is > 0; NaN compares false).
        const float* c = row + u;
        const float n[8] = {c[1], c[-1], c[2], c[-2], c[stride], c[-stride], c[2 * stride], c[-2 * stride]};
        for (const float zn : n) edge |= (zn > far) & (zn < inf);
      } else {
        auto deeper = [&](int uu, int vv) {
          if (uu < 0 || vv < 0 || uu >= w || vv >= h) return false;
          const float zn = d.ptr<float>(vv)[uu];
          return isValidDepth(zn) && zn > far;
        };
        edge = deeper(u + 1, v) || deeper(u - 1, v) || deeper(u, v + 1) || deeper(u, v - 1) || deeper(u + 2, v) ||
               deeper(u - 2, v) || deeper(u, v + 2) || deeper(u, v - 2);
      }
      if (edge) {
        e.points.push_back(view.projection.unproject(u, v, z));
        e.pixels.emplace_back(u, v);
      }
    }
  }
  return e;
}

/// One edge pixel per step x step image block: the one nearest the block's centre (ties: the
/// first in raster order). About one per step pixels along an edge of any direction (up to
/// sqrt(2) more on diagonals), where a rule on u + v alone keeps all or none of an anti-diagonal
/// edge.
EdgePoints thinToBlocks(const EdgePoints& all, int step, int width, int height) {
  if (step <= 1) return all;
  const int bw = (width + step - 1) / step, bh = (height + step - 1) / step;
  std::vector<int> chosen(static_cast<std::size_t>(bw) * static_cast<std::size_t>(bh), -1);
  std::vector<int> best_d2(chosen.size(), 0);
  const int c = step - 1;  // twice the centre offset within a block
  for (std::size_t i = 0; i < all.pixels.size(); ++i) {
    const int u = all.pixels[i].x(), v = all.pixels[i].y();
    const std::size_t b = static_cast<std::size_t>(v / step) * static_cast<std::size_t>(bw) + static_cast<std::size_t>(u / step);
    const int du = 2 * (u % step) - c, dv = 2 * (v % step) - c;
    const int d2 = du * du + dv * dv;
    if (chosen[b] < 0 || d2 < best_d2[b]) {
      chosen[b] = static_cast<int>(i);
      best_d2[b] = d2;
    }
  }
  EdgePoints e;
  for (int i : chosen)
    if (i >= 0) {
      e.points.push_back(all.points[static_cast<std::size_t>(i)]);
      e.pixels.push_back(all.pixels[static_cast<std::size_t>(i)]);
    }
  return e;
}

}  // namespace

EdgePoints findEdgePoints(const DepthView& view, const EdgeTermParams& p) {
  validate(p);
  return thinToBlocks(checkerboardEdgePixels(view, p), std::max(1, p.pixel_step / 2), view.depth_m.cols, view.depth_m.rows);
}

struct EdgeTargets::Index {
  std::vector<Eigen::Vector3d> points;   ///< target edge points with a line direction
  std::vector<Eigen::Vector3d> n1, n2;   ///< unit normals of the local edge line
  PointCloud3 cloud;
  std::unique_ptr<EdgeTree> tree;
};

EdgeTargets::EdgeTargets(const DepthView& target, const EdgeTermParams& p) : index_(std::make_unique<Index>()), params_(p) {
  validate(p);
  const EdgePoints et = checkerboardEdgePixels(target, p);  // the nearest edge pixel is within 1-2 px
  const std::size_t k = static_cast<std::size_t>(p.line_neighbours);
  if (et.points.size() < k) return;
  // Line directions from the k nearest edge points of each one (a tree over all edge points).
  PointCloud3 all{&et.points};
  EdgeTree all_tree(3, all, nanoflann::KDTreeSingleIndexAdaptorParams(10));
  all_tree.buildIndex();
  std::vector<std::uint32_t> index(k);
  std::vector<double> sq(k);
  for (const Eigen::Vector3d& x0 : et.points) {
    if (all_tree.knnSearch(x0.data(), k, index.data(), sq.data()) < k) continue;
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (std::size_t j = 0; j < k; ++j) mean += et.points[index[j]];
    mean /= static_cast<double>(k);
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    for (std::size_t j = 0; j < k; ++j) {
      const Eigen::Vector3d x = et.points[index[j]] - mean;
      cov += x * x.transpose();
    }
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
    eig.computeDirect(cov);
    const Eigen::Vector3d ev = eig.eigenvalues();
    if (!(ev[2] > 4.0 * ev[1])) continue;  // no dominant direction
    index_->points.push_back(x0);
    index_->n1.push_back(eig.eigenvectors().col(0).normalized());
    index_->n2.push_back(eig.eigenvectors().col(1).normalized());
  }
  if (index_->points.empty()) return;
  index_->cloud.points = &index_->points;
  index_->tree = std::make_unique<EdgeTree>(3, index_->cloud, nanoflann::KDTreeSingleIndexAdaptorParams(10));
  index_->tree->buildIndex();
}

EdgeTargets::~EdgeTargets() = default;

std::size_t EdgeTargets::size() const { return index_->points.size(); }

std::vector<PointToPlane> EdgeTargets::terms(const EdgePoints& source, const Isometry3& T_target_source,
                                             double max_distance_m) const {
  std::vector<PointToPlane> out;
  if (!index_->tree || !T_target_source.matrix().allFinite() || !(max_distance_m > 0)) return out;
  const double max_d2 = max_distance_m * max_distance_m;
  for (std::size_t i = 0; i < source.points.size(); ++i) {
    const Eigen::Vector3d q = T_target_source * source.points[i];
    std::uint32_t j = 0;
    double d2 = 0.0;
    if (index_->tree->knnSearch(q.data(), 1, &j, &d2) < 1 || d2 > max_d2) continue;
    out.push_back(PointToPlane{source.points[i], index_->points[j], index_->n1[j], params_.weight});
    out.push_back(PointToPlane{source.points[i], index_->points[j], index_->n2[j], params_.weight});
  }
  return out;
}

std::vector<PointToPlane> edgeTerms(const DepthView& source, const DepthView& target, const Isometry3& T_target_source,
                                    const EdgeTermParams& p) {
  const EdgeTargets targets(target, p);
  return targets.terms(findEdgePoints(source, p), T_target_source, p.max_distance_m);
}

}  // namespace gasp
