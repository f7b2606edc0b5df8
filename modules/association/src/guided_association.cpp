#include "gasp/association/guided_association.h"

#include <nanoflann.hpp>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "gasp/association/feature_sets.h"
#include "gasp/core/error.h"

namespace gasp {

namespace {

struct CentroidCloud {
  std::vector<Eigen::Vector3d> points;
  std::size_t kdtree_get_point_count() const { return points.size(); }
  double kdtree_get_pt(std::size_t i, std::size_t d) const { return points[i][static_cast<Eigen::Index>(d)]; }
  template <class BBox>
  bool kdtree_get_bbox(BBox&) const { return false; }
};
using CentroidTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, CentroidCloud>,
                                                         CentroidCloud, 3, std::uint32_t>;

struct Candidate {
  int a = -1, b = -1;
  double hat = std::numeric_limits<double>::infinity();
  double sq_distance = std::numeric_limits<double>::infinity();
  bool betterThan(const Candidate& o) const {
    if (hat != o.hat) return hat < o.hat;
    if (sq_distance != o.sq_distance) return sq_distance < o.sq_distance;
    return a != o.a ? a < o.a : b < o.b;
  }
};

}  // namespace

void validate(const GuidedAssociationParams& p) {
  if (!(p.max_distance_m > 0.0) || !std::isfinite(p.max_distance_m))
    throw Error("GuidedAssociationParams.max_distance_m must be finite and > 0");
  if (!(p.max_normal_angle_deg > 0.0 && p.max_normal_angle_deg <= 180.0))
    throw Error("GuidedAssociationParams.max_normal_angle_deg must be in (0, 180]");
  if (!(p.lambda >= 0.0 && p.lambda <= 1.0)) throw Error("GuidedAssociationParams.lambda must be in [0, 1]");
}

std::vector<PatchAssociation> guidedAssociations(const std::vector<PatchGeometry>& a,
                                                 const std::vector<PatchGeometry>& b,
                                                 const std::vector<std::vector<Feature>>& qa,
                                                 const std::vector<std::vector<Feature>>& qb,
                                                 const Isometry3& T_b_a, const AssociationParams& association,
                                                 const GuidedAssociationParams& params) {
  validate(params);
  validate(association);
  if (qa.size() != a.size() || qb.size() != b.size())
    throw Error("guidedAssociations: one feature set per patch expected");
  if (!T_b_a.matrix().allFinite()) return {};

  CentroidCloud cloud;
  std::vector<int> cloud_to_b;
  for (std::size_t j = 0; j < b.size(); ++j)
    if (!qb[j].empty() && isUsable(b[j])) {
      cloud.points.push_back(b[j].centroid);
      cloud_to_b.push_back(static_cast<int>(j));
    }
  if (cloud.points.empty()) return {};
  CentroidTree tree(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(10));
  tree.buildIndex();

  const double sq_gate = params.max_distance_m * params.max_distance_m;
  const double min_cos = std::cos(params.max_normal_angle_deg * M_PI / 180.0);
  // Each patch of A is searched by itself (in parallel, one scratch per thread); the results are
  // then taken in patch order, so they do not depend on the thread count.
  struct Scratch {
    EditDistanceWorkspace ws;
    std::vector<std::pair<std::uint32_t, double>> found;  // (point, squared distance)
  };
  tbb::enumerable_thread_specific<Scratch> scratch;
  std::vector<Candidate> best_per_a(a.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, a.size(), 16), [&](const tbb::blocked_range<std::size_t>& range) {
    Scratch& s = scratch.local();
    for (std::size_t i = range.begin(); i != range.end(); ++i) {
      if (qa[i].empty() || !isUsable(a[i])) continue;
      const Eigen::Vector3d c = T_b_a * a[i].centroid;
      const Eigen::Vector3d n = (T_b_a.linear() * a[i].normal).normalized();
      s.found.clear();
      tree.radiusSearch(c.data(), sq_gate, s.found, nanoflann::SearchParams(32, 0.0F, false));
      Candidate& best = best_per_a[i];
      for (const auto& hit : s.found) {
        const int j = cloud_to_b[hit.first];
        const auto& pb = b[static_cast<std::size_t>(j)];
        if (n.dot(pb.normal.normalized()) < min_cos) continue;
        const double denom = static_cast<double>(qa[i].size() + qb[static_cast<std::size_t>(j)].size());
        const double limit = std::min(params.lambda, best.hat);
        const double d = featureSetDistance(qa[i], qb[static_cast<std::size_t>(j)], association.match,
                                            association.costs, limit * denom * (1.0 + 1e-9), s.ws);
        if (d == kExceedsBound) continue;
        Candidate cand{static_cast<int>(i), j, d / denom, hit.second};
        if (cand.hat <= params.lambda && cand.betterThan(best)) best = cand;
      }
    }
  });
  std::vector<Candidate> best_of_a;
  for (const Candidate& c : best_per_a)
    if (c.b >= 0) best_of_a.push_back(c);
  // One-to-one: a patch of B keeps its best chooser.
  std::vector<int> owner(b.size(), -1);
  for (std::size_t k = 0; k < best_of_a.size(); ++k) {
    int& o = owner[static_cast<std::size_t>(best_of_a[k].b)];
    if (o < 0 || best_of_a[k].betterThan(best_of_a[static_cast<std::size_t>(o)])) o = static_cast<int>(k);
  }
  std::vector<PatchAssociation> out;
  for (std::size_t k = 0; k < best_of_a.size(); ++k)
    if (owner[static_cast<std::size_t>(best_of_a[k].b)] == static_cast<int>(k))
      out.push_back({best_of_a[k].a, best_of_a[k].b, best_of_a[k].hat});
  return out;
}

}  // namespace gasp
