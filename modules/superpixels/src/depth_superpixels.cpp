#include "gasp/superpixels/depth_superpixels.h"

#include <Eigen/Eigenvalues>

#include <chrono>
#include <cmath>
#include <set>

#include "gasp/core/depth_image.h"
#include "gasp/core/error.h"
#include "gasp/superpixels/area_kmeans.h"
#include "gasp/superpixels/normals.h"
#include "gasp/superpixels/patch_cleanup.h"
#include "gasp/superpixels/smooth_components.h"
#include "pixel_area.h"

namespace gasp {

namespace {

class StageTimer {
 public:
  double lap() {
    const auto now = std::chrono::steady_clock::now();
    const double ms = std::chrono::duration<double, std::milli>(now - last_).count();
    last_ = now;
    return ms;
  }

 private:
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

}  // namespace

double SurfacePatch::radius() const { return std::sqrt(area_m2 / M_PI); }

void validate(const SuperpixelParams& p) {
  auto require = [](bool ok, const char* what) {
    if (!ok) throw Error(std::string("superpixel parameters: ") + what);
  };
  require(p.discontinuity_abs_m >= 0 && p.discontinuity_rel >= 0, "discontinuity thresholds must be >= 0");
  require(p.normal_window_px_per_m > 0, "normal_window_px_per_m must be > 0");
  require(p.normal_min_radius_px >= 1 && p.normal_max_radius_px >= p.normal_min_radius_px,
          "need 1 <= normal_min_radius_px <= normal_max_radius_px");
  require(p.max_crease_angle_deg > 0 && p.max_neighbour_normal_angle_deg > 0, "angles must be > 0");
  require(p.target_patch_area_m2 > 0 && std::isfinite(p.target_patch_area_m2), "target_patch_area_m2 must be > 0");
  require(p.kmeans_iterations >= 1, "kmeans_iterations must be >= 1");
  require(p.seed_sampling_step_px >= 1, "seed_sampling_step_px must be >= 1");
  require(p.max_incidence_deg > 0 && p.max_incidence_deg < 90, "max_incidence_deg must be in (0, 90)");
  require(p.min_patch_pixels >= 1 && p.min_component_pixels >= 1, "minimum sizes must be >= 1");
}

void computePatchRecords(SuperpixelSegmentation& seg, int count, const OrganizedPointCloud& cloud,
                         const DepthLinks& links, const cv::Mat& normals, const CameraIntrinsics& k,
                         const SuperpixelParams& p) {
  const int w = cloud.width, h = cloud.height;
  const float min_cos = static_cast<float>(std::cos(p.max_incidence_deg * M_PI / 180.0));
  seg.patches.assign(static_cast<std::size_t>(count), SurfacePatch{});
  std::vector<Eigen::Vector3d> sum_p(seg.patches.size(), Eigen::Vector3d::Zero());
  std::vector<Eigen::Matrix3d> sum_pp(seg.patches.size(), Eigen::Matrix3d::Zero());
  std::vector<Eigen::Vector3d> sum_n(seg.patches.size(), Eigen::Vector3d::Zero());
  std::vector<cv::Point> lo(seg.patches.size(), cv::Point(w, h)), hi(seg.patches.size(), cv::Point(-1, -1));
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u) {
      const int l = seg.labels.at<int>(v, u);
      if (l < 0) continue;
      const Eigen::Vector3d q = cloud.at(u, v).cast<double>();
      auto& patch = seg.patches[static_cast<std::size_t>(l)];
      ++patch.pixel_count;
      sum_p[l] += q;
      sum_pp[l] += q * q.transpose();
      const cv::Vec3f& n = normals.at<cv::Vec3f>(v, u);
      sum_n[l] += Eigen::Vector3d(n[0], n[1], n[2]);  // zero where the pixel has no normal
      lo[l] = cv::Point(std::min(lo[l].x, u), std::min(lo[l].y, v));
      hi[l] = cv::Point(std::max(hi[l].x, u), std::max(hi[l].y, v));
    }
  for (int l = 0; l < count; ++l) {
    auto& patch = seg.patches[static_cast<std::size_t>(l)];
    patch.id = l;
    const double n = patch.pixel_count;
    patch.centroid = sum_p[l] / n;
    patch.covariance = sum_pp[l] / n - patch.centroid * patch.centroid.transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(patch.covariance);
    const Eigen::Vector3d ev = eig.eigenvalues().cwiseMax(0.0);
    patch.planarity = ev(1) > 0 ? 1.0 - ev(0) / ev(1) : 0.0;
    if (sum_n[l].norm() > 1e-9) {
      patch.normal = sum_n[l].normalized();
    } else {  // no pixel with a normal: the covariance's least direction, facing the camera
      patch.normal = eig.eigenvectors().col(0);
      if (patch.normal.dot(patch.centroid) > 0) patch.normal = -patch.normal;
    }
    patch.bbox = cv::Rect(lo[l], hi[l] + cv::Point(1, 1));
  }
  std::vector<std::set<int>> adjacent(static_cast<std::size_t>(count));
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u) {
      const int l = seg.labels.at<int>(v, u);
      if (l < 0) continue;
      const Eigen::Vector3f& q = cloud.at(u, v);
      const auto& patch = seg.patches[static_cast<std::size_t>(l)];
      const cv::Vec3f& pn = normals.at<cv::Vec3f>(v, u);
      const Eigen::Vector3f n = cv::norm(pn) > 0 ? Eigen::Vector3f(pn[0], pn[1], pn[2])
                                                 : patch.normal.cast<float>();
      seg.patches[static_cast<std::size_t>(l)].area_m2 += detail::pixelArea(q, n, k, min_cos);
      auto link = [&](int uu, int vv) {
        const int m = seg.labels.at<int>(vv, uu);
        if (m >= 0 && m != l) {
          adjacent[l].insert(m);
          adjacent[m].insert(l);
        }
      };
      if (links.right(v * w + u)) link(u + 1, v);
      if (links.down(v * w + u)) link(u, v + 1);
    }
  seg.adjacency.assign(static_cast<std::size_t>(count), {});
  for (int l = 0; l < count; ++l) seg.adjacency[l].assign(adjacent[l].begin(), adjacent[l].end());
}

SuperpixelSegmentation segmentDepthSuperpixels(const cv::Mat& depth_m, const CameraIntrinsics& k,
                                               const SuperpixelParams& p) {
  validate(p);
  StageTimer timer;
  SuperpixelSegmentation seg;
  const OrganizedPointCloud cloud = backProject(depth_m, k);  // checks type and size
  seg.stats.valid_pixels = cloud.countValid();
  seg.timings.cloud_ms = timer.lap();

  const DepthLinks links(cloud, p);
  const SurfaceNormals normals = estimateNormals(cloud, links, p);
  seg.timings.normals_ms = timer.lap();

  const SmoothComponents components = segmentSmoothComponents(links, normals, p);
  seg.timings.components_ms = timer.lap();

  AreaPatches patches = splitIntoAreaPatches(components.labels, components.count, cloud, normals, k, p);
  seg.timings.kmeans_ms = timer.lap();

  seg.labels = patches.labels;
  const int count = cleanUpPatches(seg.labels, cloud, links, normals, k, p);
  seg.timings.cleanup_ms = timer.lap();

  computePatchRecords(seg, count, cloud, links, normals.normals, k, p);
  for (const auto& patch : seg.patches) seg.stats.assigned_pixels += static_cast<std::size_t>(patch.pixel_count);
  seg.stats.dropped_pixels = seg.stats.valid_pixels - seg.stats.assigned_pixels;
  seg.timings.patches_ms = timer.lap();
  return seg;
}

}  // namespace gasp
