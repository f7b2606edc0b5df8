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
#include "gasp/superpixels/superpixel_params.h"

namespace gasp {

/// Columns per cell: the rows' mean pitch over the columns' step, rounded, at least 1.
int rangeBinColumns(const RangeScan& scan);

/// The binned range image [m] (CV_32FC1, 0 = no return) and its spherical grid; `link` gives the
/// discontinuity rule of the nearest surface. Throws gasp::Error for a scan without rows or
/// columns, elevations that do not ascend, or azimuths that are not evenly spaced.
std::pair<cv::Mat, ViewProjection> binRangeScan(const RangeScan& scan, const SmoothSurfaceParams& link);

/// The segmented view of a sweep (sensor frame: MRPT's LiDAR frame, x ahead, z up). `params`
/// must have processing_step_px = 1 (lidarSuperpixelParams() is a LiDAR's defaults).
DepthView makeRangeView(const RangeScan& scan, const SuperpixelParams& params);

/// The segmentation's defaults for a rotating LiDAR (the params file's `lidar_segment`): patches
/// of 0.25 m^2 (a 16-laser sensor's rows are 35 cm apart at 10 m), windows and minimum sizes in
/// binned cells, and range noise that does not grow with the square of the range.
SuperpixelParams lidarSuperpixelParams();

/// Range noise of the LiDAR the defaults are for (1 sigma) [m]: the simulator's, a VLP-16's.
constexpr double kLidarRangeSigmaM = 0.02;

/// The pair pipeline's defaults for LiDAR views, from the camera's by two rules: lengths that
/// compare patch centroids (association, RANSAC, guided verification, the dense rounds' gates)
/// grow with the patch radius, sqrt(0.25 / 0.004) = 7.9 times; lengths that compare points (the
/// solvers' noise and loss scale, the free-space gate) follow the range noise, which does not
/// grow with the range. Every cell is sampled (a binned sweep has fewer cells than the camera's
/// sampled pixels), and the edge terms and the slide scan are off (docs/lidar.md).
PairParams lidarPairParams();

}  // namespace gasp
