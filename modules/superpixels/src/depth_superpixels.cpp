#include "gasp/superpixels/depth_superpixels.h"

#include <chrono>
#include <cmath>
#include <optional>

#include "gasp/core/error.h"
#include "gasp/superpixels/area_kmeans.h"
#include "gasp/superpixels/normals.h"
#include "gasp/superpixels/patch_cleanup.h"
#include "gasp/superpixels/smooth_components.h"
#include "coarse_grid.h"
#include "full_resolution.h"
#include "patch_records.h"
#include "region_growing.h"

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
  require(p.surfaces.discontinuity_abs_m >= 0 && p.surfaces.discontinuity_rel >= 0, "discontinuity thresholds must be >= 0");
  require(p.surfaces.normal_window_px_per_m > 0, "normal_window_px_per_m must be > 0");
  require(p.surfaces.normal_min_radius_px >= 1 && p.surfaces.normal_max_radius_px >= p.surfaces.normal_min_radius_px,
          "need 1 <= normal_min_radius_px <= normal_max_radius_px");
  require(p.surfaces.max_crease_angle_deg > 0 && p.surfaces.max_neighbour_normal_angle_deg > 0, "angles must be > 0");
  require(p.target_patch_area_m2 > 0 && std::isfinite(p.target_patch_area_m2), "target_patch_area_m2 must be > 0");
  require(p.kmeans.kmeans_iterations >= 1, "kmeans_iterations must be >= 1");
  require(p.kmeans.seed_sampling_step_px >= 1, "seed_sampling_step_px must be >= 1");
  require(p.max_incidence_deg > 0 && p.max_incidence_deg < 90, "max_incidence_deg must be in (0, 90)");
  require(p.cleanup.min_patch_pixels >= 1 && p.surfaces.min_component_pixels >= 1, "minimum sizes must be >= 1");
  require(p.processing_step_px >= 1 && p.processing_step_px <= 4, "processing_step_px must be in [1, 4]");
  require(p.kmeans.kmeans_iteration_step_px >= 1, "kmeans_iteration_step_px must be >= 1");
  require(p.kmeans.kmeans_coarse_iterations >= 0, "kmeans_coarse_iterations must be >= 0");
  require(p.borders.crease_min_angle_deg > 0 && p.borders.crease_min_angle_deg < 180, "crease_min_angle_deg must be in (0, 180)");
  require(p.borders.crease_band_px >= 0, "crease_band_px must be >= 0");
  require(p.borders.plane_noise_abs_m >= 0 && p.borders.plane_noise_rel >= 0 && p.borders.plane_noise_abs_m + p.borders.plane_noise_rel > 0,
          "plane noise must be >= 0 and not both 0");
  require(p.borders.step_min_sigmas >= 0 && std::isfinite(p.borders.step_min_sigmas), "step_min_sigmas must be >= 0");
  require(p.borders.step_smoothness >= 0 && std::isfinite(p.borders.step_smoothness), "step_smoothness must be >= 0");
}

SuperpixelSegmentation segmentDepthSuperpixels(const cv::Mat& depth_m, const ViewProjection& k,
                                               const SuperpixelParams& p) {
  validate(p);
  if (!k.isPinhole() && p.processing_step_px != 1)
    throw Error("superpixel parameters: a range image is segmented with processing_step_px = 1 (its cells are "
                "already binned to the rows' pitch, see makeRangeView), got " + std::to_string(p.processing_step_px));
  StageTimer timer;
  SuperpixelSegmentation seg;
  const OrganizedPointCloud cloud = backProject(depth_m, k);  // checks type and size
  const DepthLinks links(cloud, p);
  seg.stats.valid_pixels = links.validCount();
  const bool subsampled = p.processing_step_px > 1;
  const detail::CoarseGrid grid = subsampled ? detail::makeCoarseGrid(cloud, k.pinhole(), p) : detail::CoarseGrid{};
  seg.timings.cloud_ms = timer.lap();

  // On the grid (or at full resolution with processing_step_px = 1).
  const OrganizedPointCloud& gc = subsampled ? grid.cloud : cloud;
  const ViewProjection gk = subsampled ? ViewProjection(grid.intrinsics) : k;
  const SuperpixelParams& gp = subsampled ? grid.params : p;
  const std::optional<DepthLinks> grid_links = subsampled ? std::optional<DepthLinks>(std::in_place, gc, gp) : std::nullopt;
  const DepthLinks& gl = subsampled ? *grid_links : links;
  const SurfaceNormals normals = estimateNormals(gc, gl, gp);
  seg.timings.normals_ms = timer.lap();

  const SmoothComponents components = segmentSmoothComponents(gl, normals, gp);
  seg.timings.components_ms = timer.lap();

  AreaPatches patches = splitIntoAreaPatches(components.labels, components.count, gc, normals, gk, gp);
  seg.timings.kmeans_ms = timer.lap();

  int count = cleanUpPatches(patches.labels, gc, gl, normals, gk, gp);
  seg.timings.cleanup_ms = timer.lap();

  const auto* grid_normals = reinterpret_cast<const Eigen::Vector3f*>(normals.normals.ptr<float>(0));
  detail::PixelNormals normal_of{grid_normals};
  detail::FullResolutionLabels full;
  if (subsampled) {
    full = detail::refineToFullResolution(patches.labels, count, grid, normals, cloud, links, k.pinhole(), p);
    seg.labels = full.labels;
    count = full.count;
    normal_of.cell = full.normal_cell.data();
  } else {
    seg.labels = patches.labels;
  }
  seg.timings.refine_ms = timer.lap();

  // Patch ids in raster order of first pixel, renumbered in the records' pass (the full-resolution
  // labels are not yet; the grid's are, which makes that a no-op).
  detail::recordPatches(seg, count, cloud, links, normal_of, k, p, true,
                        subsampled ? full.cell_area_factor.data() : nullptr);
  for (const auto& patch : seg.patches) seg.stats.assigned_pixels += static_cast<std::size_t>(patch.pixel_count);
  seg.stats.dropped_pixels = seg.stats.valid_pixels - seg.stats.assigned_pixels;
  seg.timings.patches_ms = timer.lap();
  return seg;
}

}  // namespace gasp
