#pragma once
/// \file range_scan.h A rotating LiDAR's sweep as a range image with its projection: one row per
/// laser, ordered by elevation, one column per azimuth step, and each cell's ray in the sensor
/// frame. MRPT's observations become one in gasp/rawlog/range_scan.h; the simulator renders one.
#include <opencv2/core.hpp>

#include <string>
#include <vector>

#include "gasp/core/pose.h"
#include "gasp/core/rolling_shutter.h"

namespace gasp {

struct RangeScan {
  double timestamp = 0.0;  ///< [s] of the sweep's start
  std::string model;       ///< MRPT's lidarModel
  /// CV_32FC1 [m], rows = lasers from the lowest elevation up, columns = azimuth steps in the
  /// order the sweep took them; 0 = no return (or outside the sensor's range).
  cv::Mat range_m;
  std::vector<double> elevation_rad;  ///< per row
  std::vector<double> azimuth_rad;    ///< per column, counter-clockwise about z from the sensor's x
  std::vector<int> laser_of_row;      ///< the observation's row (laser id) of each row
  /// CV_32FC3: each return's own unit ray in the sensor frame where the sensor's calibration
  /// gives it (a Velodyne's packets: MRPT's calibrated point cloud); empty, or zero at a cell:
  /// the row's elevation and the column's azimuth.
  cv::Mat ray;
  double sweep_duration_s = 0.0;  ///< [s] from the first column's firing to the end of the last's; 0 = not known
  Isometry3 T_robot_sensor = Isometry3::Identity();

  /// The unit ray of a cell in the sensor frame.
  Eigen::Vector3d direction(int row, int col) const;
  /// The returns as points in the sensor frame, row by row.
  std::vector<Eigen::Vector3d> points() const;
  std::size_t returnCount() const { return static_cast<std::size_t>(cv::countNonZero(range_m)); }
  /// Sets the rows from the lasers' elevations [deg] in laser-id order (sorted, lowest first,
  /// laser_of_row), the columns' azimuths, and an empty range image of that size.
  void setLayout(const std::vector<double>& elevation_deg_by_laser, std::vector<double> azimuths_rad);
};

/// Throws gasp::Error, its message starting with `who`, unless the scan is a range image GASP can
/// use: range_m CV_32FC1 with at least one row and two columns; one finite elevation per row,
/// strictly ascending, within +-90 deg; one finite azimuth per column, evenly spaced (within 1 %
/// of a non-zero step, differences taken within a turn); the ray table empty or CV_32FC3 of the
/// image's size. Columns past a whole turn (a sweep that overlaps itself) are allowed: look-ups
/// never reach them, and binning drops them.
void validateLayout(const RangeScan& scan, const std::string& who);

/// The functions below assume validateLayout() passed.
/// The signed azimuth step between columns (negative for a clockwise sweep) [rad].
double azimuthStep(const RangeScan& scan);
/// The rows' mean elevation step [rad]; a single row: |azimuthStep|.
double rowPitch(const RangeScan& scan);
/// The columns that span one row pitch: rowPitch / |azimuthStep|, rounded, at least 1 (a window
/// of that many columns per row is about square in view angle).
int columnsPerRowPitch(const RangeScan& scan);
/// True when the columns cover a whole turn (within half a step): azimuths wrap around.
bool coversWholeTurn(const RangeScan& scan);
/// The cell nearest a direction in the sensor frame: the row of the nearest elevation (false
/// beyond half a pitch from the end rows), the column of the nearest azimuth (wrapped on a whole
/// turn; false outside a partial sweep). False for the zero vector.
bool nearestCell(const RangeScan& scan, const Eigen::Vector3d& direction, int& row, int& col);

/// The time of column `col`'s firing after the sweep's start [s]: the columns span
/// sweep_duration_s at a constant rate, in the order the sweep took them (col / columns of the
/// duration; MRPT's sweepDuration is the time over the scan's azimuth span). 0 for every column
/// when the duration is 0 (not known).
double columnTime(const RangeScan& scan, int col);
/// Whether the columns carry their firing times: a known sweep duration (> 0), and columns in the
/// order the sweep took them -- not a point cloud's (rangeScanFromPoints(): azimuth bins counted
/// from azimuth 0, wherever the sweep began).
bool sweepTimed(const RangeScan& scan);
/// The sweep carried to the sensor's pose at its start (RangeScan::timestamp), for a sensor moving
/// at the constant twist `twist` (in its own frame, twistBetween()): the return of column c, fired
/// at t = columnTime(c) from the pose exp([w t]), v t relative to the start's, becomes
///   p(0) = exp([w t]) p(t) + v t
/// and is put in the cell of its new direction with its own ray, as movedScan() does (the nearer
/// where two share a cell; those beyond half a pitch from the end rows are lost). The same
/// motion model as the camera's rolling-shutter deskew (rolling_shutter.h), over a sweep instead of
/// a readout. A zero twist gives the returns unmoved. Throws gasp::Error for a scan that is not a
/// range image, one whose columns carry no times (sweepTimed()), or a twist that is not finite.
RangeScan deskewSweep(const RangeScan& scan, const CameraTwist& twist);

/// The same returns seen by the sensor moved by T_new_old (a point p becomes T_new_old p): each
/// put in the cell of its new direction (the row of the nearest elevation, the column of the
/// nearest azimuth; azimuths evenly spaced) with its own ray, the nearer where two share a cell;
/// returns beyond half a pitch from the end rows or outside the columns are lost. A real sweep
/// against itself under a known motion (tests, benchmarks). Throws gasp::Error for a scan that is
/// not a range image (validateLayout).
RangeScan movedScan(const RangeScan& scan, const Isometry3& T_new_old);

/// The model name of a scan made from a point cloud (rangeScanFromPoints()).
inline constexpr const char* kPointCloudModel = "POINT-CLOUD";

/// One sweep of a rotating LiDAR given as points without their layout (a point cloud, in the
/// sensor frame) as a range scan:
/// - rows: the rings, the clusters of the points' elevations: sorted, a new ring starts at a gap
///   of more than kMinRingGapDeg, and a cluster of fewer than kMinRingPoints points is a stray
///   elevation (a laser's offset from the sensor's centre seen at close range, a multipath
///   return), not a ring: a ring that sees mostly sky still has its few returns. A row's
///   elevation is its ring's median; the middle 90 % of a ring's elevations must span less than
///   half the distance to the nearest other ring. Points of no ring go to the nearest row within
///   half a pitch, with their own rays, or are left out.
/// - columns: a whole turn counter-clockwise from azimuth 0, at the median over the rings of the
///   median gap between a ring's consecutive azimuths.
/// - each point in the cell nearest its direction, with its own ray (the nearer where two share a
///   cell), as movedScan().
/// model is kPointCloudModel; timestamp, duration and T_robot_sensor are left to the caller.
/// Throws gasp::Error starting with `who` for fewer than two rings, more than kMaxPointCloudRows,
/// rings wider than that, or columns finer than kMinPointCloudColumnDeg (not a rotating LiDAR's
/// sweep).
RangeScan rangeScanFromPoints(const std::vector<Eigen::Vector3d>& points_sensor, const std::string& who);
/// Rotating LiDARs' rings lie at least this far apart (a 128-laser's densest, 0.125 deg).
inline constexpr double kMinRingGapDeg = 0.1;
inline constexpr int kMinRingPoints = 16;
inline constexpr int kMaxPointCloudRows = 256;
inline constexpr double kMinPointCloudColumnDeg = 0.01;

/// The lasers' elevations [deg] of a LiDAR by MRPT's lidarModel name, in laser-id order (the
/// observation's rows): VLP-16 and HDL-32E (their manuals' tables), SIM-64 (the simulator's 64
/// lasers, evenly over -24.9..+2 deg, an HDL-64E's field) and 2D scans ("2D_SCAN_*": one row at
/// 0). Empty for any other model.
std::vector<double> laserElevationsDeg(const std::string& lidar_model, int rows);

/// Whether the model's azimuth turns clockwise seen from above, as a spinning Velodyne's does
/// (VLP-16, HDL-32E, SIM-64); a 2D scan's turns counter-clockwise.
bool turnsClockwise(const std::string& lidar_model);

}  // namespace gasp
