#include "gasp/pipeline/view_degeneracy.h"

#include <Eigen/Geometry>

#include <cmath>
#include <limits>

namespace gasp {

DegeneracyAnalysis analyseViewGeometry(const SuperpixelSegmentation& view, const ViewDegeneracyParams& params) {
  Matrix6d info = Matrix6d::Zero();
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double total_area = 0.0;
  for (const auto& p : view.patches) {
    if (!countsInViewGeometry(p)) continue;
    centre += p.area_m2 * p.centroid;
    total_area += p.area_m2;
  }
  if (!(total_area > 0)) {
    DegeneracyAnalysis none;
    none.degenerate = true;
    none.reason = "the view has no usable patch";
    return none;
  }
  centre /= total_area;
  double spread = 0.0;
  for (const auto& p : view.patches) {
    if (!countsInViewGeometry(p)) continue;
    const Eigen::Vector3d n = p.normal.normalized();
    Vector6d j;
    j << n, p.centroid.cross(n);
    info += (p.area_m2 / total_area) * j * j.transpose();
    spread += p.area_m2 * (p.centroid - centre).squaredNorm();
  }
  const double radius = std::max(kMinSceneRadiusM, std::sqrt(spread / total_area));
  // Ratio only: the absolute scale of I is arbitrary here (area-normalised).
  DegeneracyParams dp;
  dp.min_eigenvalue_ratio = params.min_eigenvalue_ratio;
  dp.max_std_m = std::numeric_limits<double>::infinity();
  return analyseDegeneracy(info, centre, radius, dp);
}

}  // namespace gasp
