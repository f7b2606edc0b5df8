#pragma once
/// \file noise_model.h A Kinect-v1-like depth sensor model applied to rendered ground truth.
///
/// References:
///  - K. Khoshelham, S. O. Elberink, "Accuracy and Resolution of Kinect Depth Data for Indoor
///    Mapping Applications", Sensors 12(2), 2012 (disparity quantisation: 7.5 cm baseline,
///    1/8 px disparity steps, depth resolution growing with z^2).
///  - C. V. Nguyen, S. Izadi, D. Lovell, "Modeling Kinect Sensor Noise for Improved 3D
///    Reconstruction and Tracking", 3DIMPVT 2012 (axial sigma(z) = 0.0012 + 0.0019 (z - 0.4)^2 m;
///    unreliable depth beyond ~70-80 deg incidence and at depth edges).
#include <cstdint>
#include <opencv2/core.hpp>

#include "gasp/core/camera_intrinsics.h"
#include "gasp/sim/renderer.h"

namespace gasp::sim {

/// Parameters of the sensor model; the defaults model a Kinect v1 at 640x480.
///
/// For each pixel with a surface at true depth z:
///  1. missing when z < min_range_m or z > max_range_m;
///  2. missing at a depth discontinuity: when one of its 4-neighbours has no surface or a true
///     depth differing by more than discontinuity_fraction * min(z, z_neighbour);
///  3. missing at a grazing angle: when the angle between the pixel ray and the surface normal
///     exceeds max_incidence_deg;
///  4. otherwise z' = z + n, n ~ N(0, sigma(z)^2) with sigma(z) = sigma_a_m + sigma_b_per_m2 *
///     (z - sigma_c_m)^2 (axial noise);
///  5. disparity quantisation: d = fx * baseline_m / z' is rounded to a multiple of
///     disparity_step_px and z' = fx * baseline_m / d;
///  6. storage: z' is rounded to 1/5000 m (the TUM 16-bit PNG unit).
/// Before step 4, an optional systematic error: z is scaled by 1 + radial_depth_bias * rho^2,
/// rho^2 = ((u - cx) / fx)^2 + ((v - cy) / fy)^2, a depth error growing towards the image's
/// corners as an uncalibrated Kinect's does (it bends a plane into a bowl; off by default).
struct KinectNoiseModel {
  bool axial_noise = true;        ///< step 4
  double sigma_a_m = 0.0012;      ///< sigma(z) constant term [m] (Nguyen et al. 2012)
  double sigma_b_per_m2 = 0.0019;   ///< sigma(z) quadratic coefficient [1/m] (Nguyen et al. 2012)
  double sigma_c_m = 0.4;         ///< sigma(z) offset [m] (Nguyen et al. 2012)

  bool quantise_disparity = true;  ///< step 5
  double baseline_m = 0.075;       ///< projector-camera baseline [m] (Khoshelham & Elberink)
  double disparity_step_px = 0.125;  ///< disparity resolution [px] (1/8 px)

  double min_range_m = 0.5;  ///< nearer surfaces are missing [m]
  double max_range_m = 6.0;  ///< farther surfaces are missing [m]

  bool drop_discontinuities = true;     ///< step 2
  double discontinuity_fraction = 0.03;  ///< relative depth jump that counts as an edge

  /// Systematic radial depth error (above): 0.01 makes the corners of a 640x480 image (rho^2 ~
  /// 0.56 at fx 525) 0.56 % too deep, 8 mm at 1.4 m. Not random: the same in every frame.
  double radial_depth_bias = 0.0;

  bool drop_grazing = true;        ///< step 3
  double max_incidence_deg = 75.0;  ///< larger ray-normal angles are missing [deg]

  /// No noise, no quantisation, no dropouts: the ray-cast depth within the range limits (still
  /// stored at 1/5000 m).
  static KinectNoiseModel exact();

  /// Axial standard deviation sigma(z) [m].
  double axialSigma(double z) const;
  /// Depth spacing of adjacent disparity levels at depth z [m]: z^2 * step / (fx * baseline);
  /// quantisation moves a depth by at most half of it.
  double quantisationStep(double z, double fx) const;
  /// Throws gasp::Error for non-finite or non-positive parameters or min >= max range.
  void validate() const;
};

/// CV_8UC1 mask, 255 where the model drops the pixel (no surface, range, discontinuity, grazing).
cv::Mat dropoutMask(const RenderedFrame& frame, const KinectNoiseModel& model,
                    const CameraIntrinsics& intrinsics);

/// The random seed of one frame: a hash of (seed, frame_index), so each frame's noise is
/// independent of the order frames are generated in.
std::uint64_t frameSeed(std::uint64_t seed, int frame_index);

/// Sensor depth [m] (CV_32FC1, multiples of 1/5000 m, 0 = missing) of a rendered frame, the
/// noise drawn from std::mt19937_64(frameSeed(seed, frame_index)) in raster order.
cv::Mat sensorDepth(const RenderedFrame& frame, const KinectNoiseModel& model,
                    const CameraIntrinsics& intrinsics, std::uint64_t seed, int frame_index);

}  // namespace gasp::sim
