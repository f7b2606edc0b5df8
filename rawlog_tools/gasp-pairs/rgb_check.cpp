#include "rgb_check.h"

#include <Eigen/Geometry>

#include <cmath>

namespace gasp::pairs {

#ifdef GASP_HAVE_BASELINES
RgbCheck checkRgbRotation(const TumDataset& ds, FrameCache& cache, const PairReference& reference, std::size_t i,
                          std::size_t j, const CameraIntrinsics& rgb_camera, const baselines::EpipolarParams& params) {
  RgbCheck c;
  const auto& fi = ds.frame(i);
  const auto& fj = ds.frame(j);
  if (!fi.rgb_path || !fj.rgb_path) return c;
  c.ran = true;
  const auto e = baselines::estimateEpipolarRotation(cache.rgbd(i).bgr, cache.rgbd(j).bgr, rgb_camera, params);
  c.inliers = e.inliers;
  c.parallax_px = e.median_parallax_px;
  if (e.success) c.R_rgb = e.R_target_source;
  const auto ri = reference.at(*fi.rgb_timestamp), rj = reference.at(*fj.rgb_timestamp);
  const auto di = reference.at(fi.timestamp), dj = reference.at(fj.timestamp);
  if (ri && rj) c.T_ref = relativePose(*rj, *ri);
  if (ri && di) c.T_di_ri = relativePose(*di, *ri);
  if (rj && dj) c.T_rj_dj = relativePose(*rj, *dj);
  return c;
}
#endif

std::string rgbAngleText(const RgbCheck& c, const std::optional<Isometry3>& T_rgb) {
  if (!c.R_rgb || !T_rgb) return std::string();
  const Eigen::AngleAxisd d(c.R_rgb->transpose() * T_rgb->linear());
  return std::to_string(std::abs(d.angle()) * 180.0 / M_PI);
}

std::optional<Isometry3> toRgbStamps(const RgbCheck& c, const std::optional<Isometry3>& T_dj_di) {
  if (!T_dj_di || !c.T_di_ri || !c.T_rj_dj) return std::nullopt;
  return Isometry3(*c.T_rj_dj * *T_dj_di * *c.T_di_ri);
}

}  // namespace gasp::pairs
