#include "gasp/pipeline/plane_hypothesis.h"

#include "gasp/pipeline/view_degeneracy.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <vector>

namespace gasp {
namespace {

/// A usable patch with its unit normal, normalised once.
struct UnitPatch {
  Eigen::Vector3d normal, centroid;
  double area_m2;
};

bool onPlane(const UnitPatch& p, const Eigen::Vector3d& n, const Eigen::Vector3d& c, double cos_max) {
  return p.normal.dot(n) >= cos_max && std::abs(n.dot(p.centroid - c)) <= kPlaneOffsetM;
}

}  // namespace

std::optional<DominantPlane> dominantPlane(const SuperpixelSegmentation& view) {
  std::vector<UnitPatch> patches;
  double total = 0.0;
  for (const auto& p : view.patches)
    if (countsInViewGeometry(p)) patches.push_back({p.normal.normalized(), p.centroid, p.area_m2}), total += p.area_m2;
  if (patches.empty()) return std::nullopt;
  const double cos_max = std::cos(kPlaneAngleDeg * M_PI / 180.0);
  // Each patch's plane as a seed; the one holding the most area wins.
  const UnitPatch* best = nullptr;
  double best_area = -1.0;
  for (const UnitPatch& seed : patches) {
    double area = 0.0;
    for (const UnitPatch& p : patches)
      if (onPlane(p, seed.normal, seed.centroid, cos_max)) area += p.area_m2;
    if (area > best_area) best_area = area, best = &seed;
  }
  // The plane of the winning patches: area-weighted mean normal and centroid.
  DominantPlane plane;
  Eigen::Vector3d n = Eigen::Vector3d::Zero(), c = Eigen::Vector3d::Zero();
  for (const UnitPatch& p : patches)
    if (onPlane(p, best->normal, best->centroid, cos_max)) {
      n += p.area_m2 * p.normal;
      c += p.area_m2 * p.centroid;
      plane.area_m2 += p.area_m2;
    }
  plane.normal = n.normalized();
  plane.centroid = c / plane.area_m2;
  plane.share = plane.area_m2 / total;
  // The largest parallel plane off this one: patches with its normal, beyond its offset gate,
  // each as a seed of a plane of their own.
  for (const UnitPatch& seed : patches) {
    if (onPlane(seed, plane.normal, plane.centroid, cos_max) || seed.normal.dot(plane.normal) < cos_max) continue;
    double area = 0.0;
    for (const UnitPatch& p : patches)
      if (!onPlane(p, plane.normal, plane.centroid, cos_max) && onPlane(p, plane.normal, seed.centroid, cos_max))
        area += p.area_m2;
    plane.parallel_area_m2 = std::max(plane.parallel_area_m2, area);
  }
  return plane;
}

std::optional<Isometry3> planeHypothesis(const DominantPlane& source, const DominantPlane& target) {
  if (source.ambiguous() || target.ambiguous()) return std::nullopt;
  return alignPlanes(source, target);
}

Isometry3 alignPlanes(const DominantPlane& source, const DominantPlane& target) {
  Isometry3 T = Isometry3::Identity();
  T.linear() = Eigen::Quaterniond::FromTwoVectors(source.normal, target.normal).toRotationMatrix();
  T.translation() = target.centroid - T.linear() * source.centroid;
  return T;
}

}  // namespace gasp
