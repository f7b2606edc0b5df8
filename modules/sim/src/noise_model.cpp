#include "gasp/sim/noise_model.h"

#include <cmath>
#include <random>
#include <string>

#include "gasp/core/depth_image.h"
#include "gasp/core/error.h"

namespace gasp::sim {

KinectNoiseModel KinectNoiseModel::exact() {
  KinectNoiseModel m;
  m.axial_noise = false;
  m.quantise_disparity = false;
  m.drop_discontinuities = false;
  m.drop_grazing = false;
  return m;
}

double KinectNoiseModel::axialSigma(double z) const {
  return sigma_a_m + sigma_b_per_m2 * (z - sigma_c_m) * (z - sigma_c_m);
}

double KinectNoiseModel::quantisationStep(double z, double fx) const {
  return z * z * disparity_step_px / (fx * baseline_m);
}

void KinectNoiseModel::validate() const {
  const auto positive = [](double v, const char* field) {
    if (!(std::isfinite(v) && v > 0.0))
      throw Error(std::string("noise model: ") + field + " must be positive and finite, got " +
                  std::to_string(v));
  };
  const auto non_negative = [](double v, const char* field) {
    if (!(std::isfinite(v) && v >= 0.0))
      throw Error(std::string("noise model: ") + field + " must be >= 0 and finite, got " +
                  std::to_string(v));
  };
  non_negative(sigma_a_m, "sigma_a_m");
  non_negative(sigma_b_per_m2, "sigma_b_per_m2");
  non_negative(sigma_c_m, "sigma_c_m");
  positive(baseline_m, "baseline_m");
  positive(disparity_step_px, "disparity_step_px");
  non_negative(min_range_m, "min_range_m");
  positive(max_range_m, "max_range_m");
  positive(discontinuity_fraction, "discontinuity_fraction");
  positive(max_incidence_deg, "max_incidence_deg");
  if (!(std::isfinite(radial_depth_bias) && std::abs(radial_depth_bias) <= 0.2))
    throw Error("noise model: radial_depth_bias must be within [-0.2, 0.2], got " + std::to_string(radial_depth_bias));
  if (min_range_m >= max_range_m)
    throw Error("noise model: min_range_m (" + std::to_string(min_range_m) +
                ") must be below max_range_m (" + std::to_string(max_range_m) + ")");
}

cv::Mat dropoutMask(const RenderedFrame& frame, const KinectNoiseModel& m,
                    const CameraIntrinsics& K) {
  m.validate();
  const cv::Mat& depth = frame.depth;
  cv::Mat mask(depth.size(), CV_8UC1, cv::Scalar(0));
  const double cos_max = std::cos(m.max_incidence_deg * EIGEN_PI / 180.0);
  for (int v = 0; v < depth.rows; ++v) {
    const float* z_row = depth.ptr<float>(v);
    const auto* n_row = frame.normal.ptr<cv::Vec3f>(v);
    auto* out = mask.ptr<std::uint8_t>(v);
    for (int u = 0; u < depth.cols; ++u) {
      const double z = z_row[u];
      bool drop = !(z > 0.0) || z < m.min_range_m || z > m.max_range_m;
      if (!drop && m.drop_discontinuities) {
        const int du[4] = {-1, 1, 0, 0};
        const int dv[4] = {0, 0, -1, 1};
        for (int k = 0; k < 4 && !drop; ++k) {
          const int uu = u + du[k], vv = v + dv[k];
          if (uu < 0 || vv < 0 || uu >= depth.cols || vv >= depth.rows) continue;
          const double zn = depth.at<float>(vv, uu);
          drop = !(zn > 0.0) || std::abs(z - zn) > m.discontinuity_fraction * std::min(z, zn);
        }
      }
      if (!drop && m.drop_grazing) {
        const Eigen::Vector3d ray((u - K.cx) / K.fx, (v - K.cy) / K.fy, 1.0);
        const Eigen::Vector3d n(n_row[u][0], n_row[u][1], n_row[u][2]);
        drop = std::abs(n.dot(ray)) / ray.norm() < cos_max;
      }
      out[u] = drop ? 255 : 0;
    }
  }
  return mask;
}

std::uint64_t frameSeed(std::uint64_t seed, int frame_index) {
  // splitmix64 finaliser over a combination of both inputs.
  const auto mix = [](std::uint64_t x) {
    x += 0x9e3779b97f4a7c15ULL;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
    return x ^ (x >> 31);
  };
  return mix(mix(seed) ^ static_cast<std::uint64_t>(static_cast<std::int64_t>(frame_index)));
}

cv::Mat sensorDepth(const RenderedFrame& frame, const KinectNoiseModel& m,
                    const CameraIntrinsics& K, std::uint64_t seed, int frame_index) {
  const cv::Mat mask = dropoutMask(frame, m, K);
  std::mt19937_64 rng(frameSeed(seed, frame_index));
  std::normal_distribution<double> normal(0.0, 1.0);
  const double fb = K.fx * m.baseline_m;
  cv::Mat out(frame.depth.size(), CV_32FC1, cv::Scalar(0.0f));
  for (int v = 0; v < out.rows; ++v) {
    const float* z_row = frame.depth.ptr<float>(v);
    const auto* mask_row = mask.ptr<std::uint8_t>(v);
    auto* o = out.ptr<float>(v);
    for (int u = 0; u < out.cols; ++u) {
      if (mask_row[u]) continue;
      double z = z_row[u];
      if (m.radial_depth_bias != 0.0) {
        const double x = (u - K.cx) / K.fx, y = (v - K.cy) / K.fy;
        z *= 1.0 + m.radial_depth_bias * (x * x + y * y);
      }
      if (m.axial_noise) z += m.axialSigma(z) * normal(rng);
      if (m.quantise_disparity && z > 0.0) {
        const double d = std::round(fb / z / m.disparity_step_px) * m.disparity_step_px;
        z = d > 0.0 ? fb / d : 0.0;
      }
      const double stored = std::round(z * kTumDepthUnitsPerMetre) / kTumDepthUnitsPerMetre;
      o[u] = stored > 0.0 ? static_cast<float>(stored) : 0.0f;
    }
  }
  return out;
}

}  // namespace gasp::sim
