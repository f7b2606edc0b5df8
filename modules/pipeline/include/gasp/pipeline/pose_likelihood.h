#pragma once
/// \file pose_likelihood.h How much better one pose explains two depth views than another, as a
/// log-likelihood ratio: the certificate's uniqueness test (certify_stage.h) compares the chosen
/// pose with the best distinct alternative RANSAC found, refined like it.
///
/// Every pixel_step-th pixel of either view with valid depth is mapped by each pose into the other
/// view; only the samples that land on measured depth under both poses count, so that neither
/// pose gains by putting more of one view inside the other's image (on one large plane, a pose
/// slid along it explains the shared part exactly as well). Where a sample lands on measured depth
/// z_t, its depth residual e = z - z_t along the other camera's ray has the density
///   p(e) = w N(e; 0, sigma(z_t)^2) + (1 - w) / range,   sigma(z) = sigma_m + sigma_per_m2 z^2,
/// a Gaussian inlier with the sensor's noise and a uniform outlier (MLESAC: Torr and Zisserman,
/// 2000). Relative to the sample being an outlier it contributes
/// l = log(1 + w range N(e; 0, sigma^2) / (1 - w)) >= 0: occlusions add nothing, surface
/// explained adds up to l(0) (3.7 nats at 1 cm). With violation_nats > 0 a sample in front of the
/// measured surface by more than the free-space test's gate (a violation, visibility_check.h)
/// scores l - violation_nats: the other sensor saw that space empty, so only a random reading
/// explains it, while an occluded sample is hidden by the surface in front (the beam model of
/// range sensors: Thrun, Burgard and Fox, Probabilistic Robotics, 2005, ch. 6). Without it a pose
/// that puts a view's samples into the other's free space loses nothing by it, and on the few
/// samples both poses land a far pose fitted to them can win. The samples of one patch share that
/// patch's error (its plane, its depth bias), so they are one observation: the log-likelihood
/// ratio is the sum over both views' patches (segmentation.labels) of the mean over their
/// counted samples of l under one pose minus l under the other. A patch whose mean differs by at
/// most one nat (about 1.5 sigma of movement off its surface) counts as explained equally well:
/// the depth's correlated errors (disparity quantisation terraces, a depth bias) shift whole
/// regions by a fraction of sigma, which summed over a thousand patches would otherwise decide
/// between poses that the surfaces cannot tell apart (a slide along one plane).
/// The ratio's standard error is that of a sum of independent zero-mean patch terms,
/// sqrt(sum d_k^2): where the surfaces cannot tell two poses apart, the sensor noise of small
/// patches (a sample or two each) still moves the sum by that much.
/// A patch whose samples all land well counts about l(0), so a ratio of e^7 (about 1000) is two
/// patches' worth of surface explained.
#include <vector>

#include "gasp/core/pose.h"
#include "gasp/pipeline/depth_view.h"
#include "gasp/pipeline/visibility_check.h"

namespace gasp {

/// The noise model above: sigma(z) = 5 mm + 2.5 mm/m^2 z^2 (half the depth-agreement gate of
/// visibility_check.h, the Kinect's noise at 1-3 m with room for the model error), w = 0.5,
/// range 1 m, every 8th pixel, a dead band of one nat per patch, violations as outliers
/// (violation_nats 0; the certificate sets it, CertifyParams::violation_nats). The certificate
/// (compareAlternative()) samples the free-space test's pixels instead (VisibilityCheckParams::
/// pixel_step: every cell of a LiDAR's binned view, whose 16 rows every 8th would cut to two).
struct PoseLikelihoodParams {
  int pixel_step = 8;
  double sigma_m = 0.005;
  double sigma_per_m2 = 0.0025;
  double inlier_prior = 0.5;
  double outlier_range_m = 1.0;
  double patch_deadband_nats = 1.0;
  /// What a violating sample costs beyond an outlier [nats] (>= 0; 0: nothing); ln 10 makes it
  /// ten times less likely than an occluded one.
  double violation_nats = 0.0;
  /// The gate that tells a violation (FreeSpaceGate): the free-space test's.
  VisibilityCheckParams free_space;
};

struct LikelihoodRatio {
  double log_ratio = 0.0;       ///< log L(T_a) - log L(T_b) [nats]
  double standard_error = 0.0;  ///< sqrt of the sum of the squared patch terms [nats]
  int patches = 0;              ///< patches with a sample landing under both poses
};

/// The ratio of T_a over T_b (both T_target_source), as above; zero for views without patches
/// or without a sample landing under both. Never throws for data; a non-finite pose gives zero.
LikelihoodRatio logLikelihoodRatio(const DepthView& source, const DepthView& target, const Isometry3& T_a,
                          const Isometry3& T_b, const PoseLikelihoodParams& params = {});

/// The samples' l under one pose T_a, kept to compare it with many others at the cost of one pose
/// each (the certificate's symmetry test compares a claimed pose with nine turns): each view's
/// samples by their index in its grid of every pixel_step-th pixel, NaN where a sample lands on
/// no measured depth or is not a sample.
struct PoseSamples {
  Isometry3 T_target_source = Isometry3::Identity();
  int pixel_step = 0;  ///< of the params they were taken with
  std::vector<double> source_to_target, target_to_source;
};
PoseSamples poseSamples(const DepthView& source, const DepthView& target, const Isometry3& T_a,
                        const PoseLikelihoodParams& params = {});
/// logLikelihoodRatio(source, target, a.T_target_source, T_b, params), the same to the bit, with
/// T_a's samples taken from `a` (poseSamples() of the same views and params; throws gasp::Error
/// when `a` was taken with another pixel_step).
LikelihoodRatio logLikelihoodRatio(const DepthView& source, const DepthView& target, const PoseSamples& a,
                                   const Isometry3& T_b, const PoseLikelihoodParams& params = {});
/// The same ratio on two sweeps' own returns (both views carry DepthView::returns; zero otherwise),
/// with no binned cell's mean of different returns in between: every return of each sweep mapped
/// into the other lands on the return nearest its direction there (landOnReturns,
/// returns_stage.h); its residual is its distance from that return's plane, sigma = range_sigma_m;
/// a landing in front of that return by more than the returns' free-space gate is a violation;
/// the samples are grouped by the patch of the binned cell they belong to. params' sigma_m,
/// sigma_per_m2, pixel_step and free_space are not used.
LikelihoodRatio returnsLogLikelihoodRatio(const DepthView& source, const DepthView& target, const Isometry3& T_a,
                                          const Isometry3& T_b, const PoseLikelihoodParams& params,
                                          double range_sigma_m, double max_incidence_deg = 80.0);

}  // namespace gasp
