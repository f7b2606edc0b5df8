#include "gasp/pipeline/plane_hypothesis.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <vector>

namespace gasp {
namespace {

bool usable(const SurfacePatch& p) {
  return p.centroid.allFinite() && p.normal.allFinite() && p.area_m2 > 0.0 && p.normal.squaredNorm() > 1e-12;
}

bool onPlane(const SurfacePatch& p, const Eigen::Vector3d& n, const Eigen::Vector3d& c, double cos_max) {
  return p.normal.normalized().dot(n) >= cos_max && std::abs(n.dot(p.centroid - c)) <= kPlaneOffsetM;
}

}  // namespace

std::optional<DominantPlane> dominantPlane(const SuperpixelSegmentation& view) {
  std::vector<const SurfacePatch*> patches;
  double total = 0.0;
  for (const auto& p : view.patches)
    if (usable(p)) patches.push_back(&p), total += p.area_m2;
  if (patches.empty()) return std::nullopt;
  const double cos_max = std::cos(kPlaneAngleDeg * M_PI / 180.0);
  // Each patch's plane as a seed; the one holding the most area wins.
  const SurfacePatch* best = nullptr;
  double best_area = -1.0;
  for (const SurfacePatch* seed : patches) {
    const Eigen::Vector3d n = seed->normal.normalized();
    double area = 0.0;
    for (const SurfacePatch* p : patches)
      if (onPlane(*p, n, seed->centroid, cos_max)) area += p->area_m2;
    if (area > best_area) best_area = area, best = seed;
  }
  // The plane of the winning patches: area-weighted mean normal and centroid.
  const Eigen::Vector3d n0 = best->normal.normalized();
  DominantPlane plane;
  Eigen::Vector3d n = Eigen::Vector3d::Zero(), c = Eigen::Vector3d::Zero();
  for (const SurfacePatch* p : patches)
    if (onPlane(*p, n0, best->centroid, cos_max)) {
      n += p->area_m2 * p->normal.normalized();
      c += p->area_m2 * p->centroid;
      plane.area_m2 += p->area_m2;
    }
  plane.normal = n.normalized();
  plane.centroid = c / plane.area_m2;
  plane.share = plane.area_m2 / total;
  // The largest parallel plane off this one: patches with its normal, beyond its offset gate,
  // each as a seed of a plane of their own.
  for (const SurfacePatch* seed : patches) {
    if (onPlane(*seed, plane.normal, plane.centroid, cos_max) || seed->normal.normalized().dot(plane.normal) < cos_max)
      continue;
    double area = 0.0;
    for (const SurfacePatch* p : patches)
      if (!onPlane(*p, plane.normal, plane.centroid, cos_max) && onPlane(*p, plane.normal, seed->centroid, cos_max))
        area += p->area_m2;
    plane.parallel_area_m2 = std::max(plane.parallel_area_m2, area);
  }
  return plane;
}

std::optional<Isometry3> planeHypothesis(const SuperpixelSegmentation& source, const SuperpixelSegmentation& target) {
  const auto ps = dominantPlane(source);
  const auto pt = ps && !ps->ambiguous() ? dominantPlane(target) : std::nullopt;
  if (!pt || pt->ambiguous()) return std::nullopt;
  return alignPlanes(*ps, *pt);
}

Isometry3 alignPlanes(const DominantPlane& source, const DominantPlane& target) {
  Isometry3 T = Isometry3::Identity();
  T.linear() = Eigen::Quaterniond::FromTwoVectors(source.normal, target.normal).toRotationMatrix();
  T.translation() = target.centroid - T.linear() * source.centroid;
  return T;
}

}  // namespace gasp
