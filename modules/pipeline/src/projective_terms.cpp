#include "gasp/pipeline/projective_terms.h"

#include <algorithm>
#include <cmath>

#include "gasp/core/depth_image.h"
#include "gasp/core/error.h"

namespace gasp {

void validate(const ProjectiveTermParams& p) {
  if (p.pixel_step < 1) throw Error("ProjectiveTermParams: pixel_step must be >= 1");
  if (!(p.max_distance_m > 0) || !std::isfinite(p.max_distance_m))
    throw Error("ProjectiveTermParams: max_distance_m must be finite and > 0");
  if (!(p.max_normal_angle_deg > 0 && p.max_normal_angle_deg <= 180))
    throw Error("ProjectiveTermParams: max_normal_angle_deg must be in (0, 180]");
  if (!(p.sample_spacing_deg >= 0 && p.sample_spacing_deg <= 90))
    throw Error("ProjectiveTermParams: projective_sample_spacing_deg must be in [0, 90]");
}

int samplingStep(const ViewProjection& projection, const ProjectiveTermParams& p) {
  const double spacing_px = p.sample_spacing_deg * M_PI / 180.0 * projection.pixelsPerRadian();
  return std::max(p.pixel_step, static_cast<int>(std::lround(spacing_px)));
}

namespace {

/// The target pixel a target-frame point projects to, and the patch there; false when it lands
/// off the image or on no patch.
bool patchUnder(const DepthView& target, const Eigen::Vector3d& p_t, int& ut, int& vt, int& label) {
  double uf = 0, vf = 0;
  if (!target.projection.project(p_t, uf, vf)) return false;
  ut = static_cast<int>(std::lround(uf)), vt = static_cast<int>(std::lround(vf));
  const cv::Mat& lt = target.segmentation.labels;
  if (ut < 0 || vt < 0 || ut >= lt.cols || vt >= lt.rows) return false;
  label = lt.at<int>(vt, ut);
  return label >= 0;
}

}  // namespace

std::vector<PointToPlane> projectiveTerms(const DepthView& source, const DepthView& target,
                                          const Isometry3& T_target_source, const ProjectiveTermParams& p) {
  validate(p);
  std::vector<PointToPlane> terms;
  const cv::Mat& ls = source.segmentation.labels;
  const cv::Mat& lt = target.segmentation.labels;
  if (ls.empty() || lt.empty() || !T_target_source.matrix().allFinite()) return terms;
  const double cos_max = std::cos(p.max_normal_angle_deg * M_PI / 180.0);
  const double max_d2 = p.max_distance_m * p.max_distance_m;
  // With pixel_footprint the gate widens by the target pixel's footprint on its surface (the
  // sampled pixel's point can be that far from where the source point lands): depth * half a
  // pixel's diagonal / cos(incidence).
  const double half_pixel = target.projection.halfPixelDiagonalRad();
  const double min_cos = std::cos(target.superpixels.max_incidence_deg * M_PI / 180.0);
  const Eigen::Matrix3d R = T_target_source.linear();
  const int step = samplingStep(source.projection, p);
  for (int v = 0; v < ls.rows; v += step)
    for (int u = 0; u < ls.cols; u += step) {
      const int la = ls.at<int>(v, u);
      if (la < 0) continue;
      const float z = source.depth_m.at<float>(v, u);
      if (!isValidDepth(z)) continue;
      const Eigen::Vector3d p_s = source.projection.unproject(u, v, z);
      const Eigen::Vector3d p_t = T_target_source * p_s;
      int ut = 0, vt = 0, lb = -1;
      if (!patchUnder(target, p_t, ut, vt, lb)) continue;
      const float zt = target.depth_m.at<float>(vt, ut);
      if (!isValidDepth(zt)) continue;
      const Eigen::Vector3d q = target.projection.unproject(ut, vt, zt);
      const Eigen::Vector3d& n_t = target.segmentation.patches[static_cast<std::size_t>(lb)].normal;
      double gate2 = max_d2;
      if (p.pixel_footprint) {
        const double q_len = q.norm();
        const double cos_i = q_len > 0.0 ? std::max(std::abs(n_t.dot(q)) / q_len, min_cos) : 1.0;
        const double gate = p.max_distance_m + zt * half_pixel / cos_i;
        gate2 = std::isfinite(gate) ? gate * gate : max_d2;  // a NaN normal widens nothing
      }
      if ((q - p_t).squaredNorm() > gate2) continue;
      const Eigen::Vector3d n_s = R * source.segmentation.patches[static_cast<std::size_t>(la)].normal;
      if (n_s.dot(n_t) < cos_max) continue;
      terms.push_back(PointToPlane{p_s, q, n_t.normalized(), 1.0});
    }
  return terms;
}

std::vector<PatchCorrespondence> projectivePatchPairs(const DepthView& source, const DepthView& target,
                                                      const Isometry3& T_target_source, const ProjectiveTermParams& p) {
  validate(p);
  std::vector<PatchCorrespondence> pairs;
  const cv::Mat& lt = target.segmentation.labels;
  if (lt.empty() || !T_target_source.matrix().allFinite()) return pairs;
  const double cos_max = std::cos(p.max_normal_angle_deg * M_PI / 180.0);
  for (const SurfacePatch& a : source.segmentation.patches) {
    if (!a.centroid.allFinite() || !a.normal.allFinite()) continue;
    const Eigen::Vector3d c_t = T_target_source * a.centroid;
    int ut = 0, vt = 0, lb = -1;
    if (!patchUnder(target, c_t, ut, vt, lb)) continue;
    if (static_cast<std::size_t>(lb) >= target.segmentation.patches.size()) continue;
    const SurfacePatch& b = target.segmentation.patches[static_cast<std::size_t>(lb)];
    const Eigen::Vector3d n_s = a.normal.normalized(), n_t = b.normal.normalized();
    if (!((T_target_source.linear() * n_s).dot(n_t) >= cos_max)) continue;  // NaN fails too
    if (!((c_t - b.centroid).norm() <= p.max_distance_m)) continue;
    pairs.push_back(PatchCorrespondence{a.centroid, n_s, b.centroid, n_t, 1.0});
  }
  return pairs;
}

}  // namespace gasp
