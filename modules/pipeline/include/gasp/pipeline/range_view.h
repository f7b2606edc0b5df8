#pragma once
/// \file range_view.h A rotating LiDAR's sweep as a depth view: its range image binned to cells
/// as wide in azimuth as its rows are apart in elevation, then segmented like a depth image.
///
/// Why binned: patches of regular area and every window of the segmentation are measured in
/// pixels that are about square in view angle. A LiDAR's columns are 5-10 times closer than its
/// rows (0.2 deg against 0.4-2 deg), so a bin of that many columns makes one cell. A cell holds
/// the mean point of the returns of the bin's nearest surface (the segmentation's link rule,
/// depth_links.h, around the nearest return), and its own ray to that point: no return is moved.
#include "gasp/core/range_scan.h"
#include "gasp/core/view_projection.h"
#include "gasp/pipeline/depth_view.h"
#include "gasp/pipeline/pair_registration.h"
#include "gasp/pipeline/returns_stage.h"
#include "gasp/superpixels/superpixel_params.h"

#include <string>
#include <vector>

namespace gasp {

/// Columns per cell: the rows' mean pitch over the columns' step, rounded, at least 1. Throws
/// gasp::Error for a scan that is not a range image (validateLayout, range_scan.h).
int rangeBinColumns(const RangeScan& scan);

/// The binned range image [m] (CV_32FC1, 0 = no return) and its spherical grid. A bin's nearest
/// surface: its returns within params.surfaces.discontinuity_abs_m plus what a surface seen at
/// params.max_incidence_deg spans across the bin. Throws gasp::Error for a scan that is not a
/// range image (validateLayout).
std::pair<cv::Mat, ViewProjection> binRangeScan(const RangeScan& scan, const SuperpixelParams& params);

/// The segmented view of a sweep (sensor frame: MRPT's LiDAR frame, x ahead, z up), carrying its
/// returns with their normals (`returns`' settings) for the pair's last stage (returns_stage.h).
/// `params` must have processing_step_px = 1 (lidarSuperpixelParams() are a LiDAR's).
DepthView makeRangeView(const RangeScan& scan, const SuperpixelParams& params, const ReturnsRefineParams& returns = {});

/// A rotating LiDAR's own parameters (the params file's section `lidar`, docs/lidar.md): the
/// pair pipeline's values for its sweeps follow from them and the camera's defaults
/// (lidarPairParams), and so do the returns' rounds (returnsRefineParams, returns_stage.h).
struct LidarParams {
  /// Target patch area [m^2]: about 5 binned cells of a 16-laser sensor at 10 m, 60 at 2.5 m.
  double patch_area_m2 = 0.5;
  double range_sigma_m = 0.02;  ///< range noise (1 sigma) [m]: the simulator's, a VLP-16's
  /// The returns' rounds (ReturnsRefineParams): their gates are 15, 7.5 and 4 range_sigma_m.
  int returns_column_step = 1;
  int returns_look_up_columns = 2;
  int returns_max_rounds = 10;
  double returns_converged_m = 0.0005;
  int returns_normal_half_width = 0;  ///< 0: square in view angle (ReturnsRefineParams)
  double returns_max_flatness = 0.3;
  /// Grow a return's normal window against range_sigma_m where three adjacent rows are not flat
  /// (ReturnsRefineParams::normal_noise_m): most 64-laser returns in a room get a normal, which
  /// the 64-laser pair pays for in its segmentation (docs/lidar.md "The returns' normals").
  bool returns_normal_growth = true;
  /// The certificate's symmetry test for sweeps (CertifyParams::symmetry_test): a sweep sees all
  /// around, so in a near-square room a pose turned a quarter matches walls to walls.
  bool symmetry_test = true;
  /// CertifyParams::violation_nats for sweeps: a sample in the other sweep's free space is ten
  /// times less likely than an occluded one (ln 10).
  double violation_nats = 2.302585092994046;
  /// The dense rounds' samples at least this far apart in view angle [deg]
  /// (ProjectiveTermParams::sample_spacing_deg): a camera's every 8th pixel at 525 px focal
  /// length. Binned cells of 16 and 32 lasers (1.4-2 deg) are each sampled; 64 lasers' (0.4 deg)
  /// every second one each way.
  double dense_sample_spacing_deg = 0.873;
  /// The ground search (ground_search.h) for sweeps whose association gives no claimed pose, and
  /// the farthest it looks for the source sensor from the target's, along each axis of the ground
  /// [m, at most twice the search's 40 m range].
  bool ground_search = true;
  double ground_search_max_offset_m = 30.0;
  /// Stage 8 (sweep_motion.h) for sweeps whose columns carry their times: each sweep's own motion
  /// estimated with the pose, and moving sweeps deskewed and registered again. The twists' prior
  /// (SweepMotionParams): a walking or driving robot's speed and turn rate (1 sigma per axis).
  bool sweep_motion = true;
  double sweep_speed_sigma_mps = 2.0;
  double sweep_rate_sigma_radps = 1.0;
};

/// Throws gasp::Error naming the first parameter out of its range.
void validate(const LidarParams& params);

/// The returns' rounds of `params`: gates of 15, 7.5 and 4 range_sigma_m (0.3, 0.15, 0.08 m at
/// 2 cm), their basin test restarted half the first gate away and held within range_sigma_m, the
/// other settings as given.
ReturnsRefineParams returnsRefineParams(const LidarParams& params = {});

/// The segmentation for binned sweeps: patches of params.patch_area_m2, at full resolution of the
/// binned image, windows and minimum sizes in binned cells, discontinuities from the range noise
/// (it does not grow with the square of the range).
SuperpixelParams lidarSuperpixelParams(const LidarParams& params = {});

/// How much longer a LiDAR view's centroid comparisons are than a camera view's: the ratio of
/// the patch radii, sqrt(patch_area_m2 / SuperpixelParams{}.target_patch_area_m2).
double lidarCentroidScale(const LidarParams& params = {});

/// `camera`'s association settings for LiDAR views: the lengths that compare patch centroids
/// (the feature sets' ordering radius, the match's radius deviation) times lidarCentroidScale().
AssociationParams lidarAssociationParams(const AssociationParams& camera, const LidarParams& params = {});

/// The pair pipeline's values for LiDAR views, from a camera's (`camera`: the defaults, or a
/// params file's pair sections) by two rules: lengths that compare patch centroids (association,
/// RANSAC, guided verification, the dense rounds' gates) grow with the patch radius
/// (lidarCentroidScale()); lengths that compare points (the solvers' noise and loss scale, the
/// free-space gate) follow the range noise. Every cell is sampled (a binned sweep has fewer cells
/// than a camera's sampled pixels), the edge terms and the slide scan are off (docs/lidar.md),
/// the segmentation is lidarSuperpixelParams(params) and the returns' rounds are
/// returnsRefineParams(params); the certificate's symmetry test and its likelihood's violation
/// charge are params.symmetry_test and params.violation_nats. The rest (counts, limits, switches)
/// is the camera's as given.
PairParams lidarPairParams(const LidarParams& params, const PairParams& camera);
/// The same from the camera's defaults.
PairParams lidarPairParams(const LidarParams& params = {});

/// Two sweeps registered with no prior: each made a view (makeRangeView, concurrently), then
/// registerViews(), whose last stage refines a claimed pose on the returns (returns_stage.h).
struct RangePairResult {
  PairResult pair;
  double segmentation_ms = 0.0;  ///< both views' binning, segmentation and returns' normals
};
/// Throws gasp::Error for invalid params or a scan that is not a range image.
RangePairResult registerRangeScans(const RangeScan& source, const RangeScan& target, const PairParams& params);
/// The same with a LiDAR's parameters: lidarPairParams(lidar).
RangePairResult registerRangeScans(const RangeScan& source, const RangeScan& target, const LidarParams& lidar = {});

}  // namespace gasp
