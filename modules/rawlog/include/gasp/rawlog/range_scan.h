#pragma once
/// \file range_scan.h MRPT's range observations as a RangeScan (gasp/core/range_scan.h): the
/// first step of GASP on range observations (issue 49).
///
/// MRPT 2.5's CObservationRotatingScan stores the ranges, the first column's azimuth, the span and
/// the model's name, but not the lasers' elevations: they come from the model
/// (laserElevationsDeg()). Two of its conventions are read as MRPT 2.5.8 writes them:
/// - fromVelodyne() allocates rowCount times the columns it fills (its column index is divided by
///   the laser count), so a scan whose returns all lie in the first columnCount / rowCount columns
///   is read as that many columns;
/// - a Velodyne's azimuth turns clockwise seen from above (as the sensor spins), a 2D scan's (and
///   the ray's here) counter-clockwise about the sensor's z from its x axis.
#include "gasp/core/range_scan.h"
#include "gasp/rawlog/rgbd_frame.h"

#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/obs/CObservationPointCloud.h>
#include <mrpt/obs/CObservationRotatingScan.h>

#include <string>

namespace gasp {

/// The scan as a range image with its projection. Throws gasp::Error naming the model for one
/// whose elevations are not known, or when they do not match its rows, and for an empty scan.
RangeScan rangeScanFrom(const mrpt::obs::CObservationRotatingScan& scan);
/// Any observation CObservationRotatingScan::fromGeneric() converts (CObservationVelodyneScan,
/// CObservation2DRangeScan), a rotating scan itself, or a CObservationPointCloud of one sweep;
/// gasp::Error naming the class otherwise.
/// A Velodyne scan's returns are MRPT's calibrated points (generatePointCloud()), each in the
/// cell of its laser and nearest column, with its own ray (`ray`): the image reproduces them
/// exactly, where uniform columns are off by up to a quarter of a degree.
/// A point cloud (its points in the sensor frame, as MRPT keeps them) gets the layout its points
/// show (rangeScanFromPoints(): rings by elevation, columns at its azimuth step), each point with
/// its own ray; MRPT 2.5.8's fromGeneric() does not convert point clouds. gasp::Error naming the
/// observation when its points do not lie on rings (not one sweep of a rotating LiDAR).
RangeScan rangeScanFrom(const mrpt::obs::CObservation& observation);

/// Whether GASP reads `observation` as a rotating LiDAR's sweep: a CObservationRotatingScan, a
/// CObservationVelodyneScan, a CObservationPointCloud, or a CObservation3DRangeScan that holds 3D
/// points and no range image (toPointsScan(); a depth camera's scan has its range image). 2D scans
/// convert too, but one row is no surface.
bool isSweepObservation(const mrpt::obs::CObservation& observation);
/// Whether `observation` hands a sweep over as bare points (a CObservationPointCloud, or a
/// CObservation3DRangeScan of points alone): points that may be another sensor's, not a rotating
/// LiDAR's rings, which rangeScanFrom() then refuses and a map leaves out.
bool isPointsObservation(const mrpt::obs::CObservation& observation);
/// What GASP takes `observation` for, in messages: "a depth image (CObservation3DRangeScan)", "a
/// LiDAR sweep (CObservationRotatingScan)", "a LiDAR sweep as 3D points (CObservation3DRangeScan
/// without a range image)", or "a CObservationFoo".
std::string observationKind(const mrpt::obs::CObservation& observation);
/// The sweep as a frame (RgbdFrame::sweep; its timestamp, sensor label, and its sensorPose as
/// T_robot_camera, the LiDAR's own frame). Throws gasp::Error starting with `what` for a sweep
/// rangeScanFrom() refuses or an observation that is not one.
RgbdFrame sweepFrameFromObservation(const mrpt::obs::CObservation& observation, const std::string& what);

/// The range unit of the rotating scans GASP writes [m]: 2 mm, as MRPT's Velodyne conversion.
inline constexpr double kRotatingScanResolutionM = 0.002;

/// `scan` as MRPT 2.5's CObservationRotatingScan (rows in laser-id order, ranges in
/// kRotatingScanResolutionM units, the model's name for its elevations), which rangeScanFrom()
/// reads back. Throws gasp::Error for a scan without a layout, with per-return rays (MRPT 2.5 has
/// no place for them), or of a model whose elevations a reader would not know.
mrpt::obs::CObservationRotatingScan toRotatingScan(const RangeScan& scan, const std::string& sensor_label);

/// `scan`'s returns as MRPT's CObservationPointCloud (a CSimplePointsMap in the sensor frame, the
/// scan's timestamp and T_robot_sensor as sensorPose): how many drivers hand a sweep over, without
/// its layout. rangeScanFrom() finds the layout again. Throws gasp::Error for a scan without a
/// layout (validateLayout).
mrpt::obs::CObservationPointCloud toPointCloud(const RangeScan& scan, const std::string& sensor_label);

/// `scan`'s returns as a CObservation3DRangeScan holding only its 3D points (hasPoints3D, no range
/// image; in the sensor frame, T_robot_sensor as sensorPose), which rangeScanFrom() reads as a
/// point cloud. The form of a sweep MRPT 2.5's points maps insert at the robot's pose: they insert
/// no rotating scan, and place a CObservationPointCloud at its sensorPose alone. Throws gasp::Error
/// for a scan without a layout (validateLayout).
mrpt::obs::CObservation3DRangeScan toPointsScan(const RangeScan& scan, const std::string& sensor_label);

}  // namespace gasp
