#include "gasp/rawlog/range_scan.h"

#include <mrpt/maps/CPointsMap.h>
#include <mrpt/maps/CSimplePointsMap.h>
#include <mrpt/obs/CObservationPointCloud.h>
#include <mrpt/obs/CObservationRotatingScan.h>
#include <mrpt/obs/CObservationVelodyneScan.h>
#include <mrpt/core/Clock.h>
#include <mrpt/poses/CPose3D.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include "gasp/core/error.h"
#include "gasp/rawlog/observation_conversion.h"

namespace gasp {

RangeScan rangeScanFrom(const mrpt::obs::CObservationRotatingScan& scan) {
  const int rows = scan.rowCount, cols_allocated = scan.columnCount;
  if (rows == 0 || cols_allocated == 0 || scan.rangeImage.rows() != rows || scan.rangeImage.cols() != cols_allocated)
    throw Error("rotating scan '" + scan.sensorLabel + "': empty, or its range image is not rowCount x columnCount");
  const std::vector<double> elevations = laserElevationsDeg(scan.lidarModel, rows);
  if (elevations.empty())
    throw Error("rotating scan '" + scan.sensorLabel + "': the lasers' elevations of lidarModel '" + scan.lidarModel +
                "' are not known (VLP-16, HDL-32E, SIM-64 and 2D scans are)");
  if (static_cast<int>(elevations.size()) != rows)
    throw Error("rotating scan '" + scan.sensorLabel + "': lidarModel '" + scan.lidarModel + "' has " +
                std::to_string(elevations.size()) + " lasers, the scan " + std::to_string(rows) + " rows");
  // MRPT 2.5's fromVelodyne() layout: the returns all in the first columnCount / rowCount columns.
  int cols = cols_allocated;
  if (rows > 1 && cols_allocated % rows == 0) {
    const int used = cols_allocated / rows;
    bool beyond = false;
    for (int r = 0; r < rows && !beyond; ++r)
      for (int c = used; c < cols_allocated && !beyond; ++c) beyond = scan.rangeImage(r, c) != 0;
    if (!beyond) cols = used;
  }
  RangeScan out;
  out.timestamp = mrpt::Clock::toDouble(scan.timestamp);
  out.model = scan.lidarModel;
  out.sweep_duration_s = scan.sweepDuration;
  out.T_robot_sensor = fromCPose3D(scan.sensorPose);
  // Clockwise for a Velodyne (its azimuth follows the spin), counter-clockwise for a 2D scan.
  const double sign = turnsClockwise(scan.lidarModel) ? -1.0 : 1.0;
  std::vector<double> azimuths;
  for (int c = 0; c < cols; ++c) azimuths.push_back(sign * (scan.startAzimuth + scan.azimuthSpan * c / cols));
  out.setLayout(elevations, std::move(azimuths));
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      const double d = scan.rangeImage(out.laser_of_row[static_cast<std::size_t>(r)], c) * scan.rangeResolution;
      if (d > 0.0 && d >= scan.minRange && d <= scan.maxRange) out.range_m.at<float>(r, c) = static_cast<float>(d);
    }
  return out;
}

namespace {

/// MRPT's calibrated points of a Velodyne scan, into the cells of `out` (its layout set).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnon-virtual-dtor"  // MRPT's wrapper has no virtual destructor
class CellFiller final : public mrpt::obs::CObservationVelodyneScan::PointCloudStorageWrapper {
 public:
  CellFiller(RangeScan& out, double start_rad, double span_rad) : out_(out), start_(start_rad), span_(span_rad) {
    row_of_laser_.assign(out.laser_of_row.size(), 0);
    for (std::size_t row = 0; row < out.laser_of_row.size(); ++row)
      row_of_laser_[static_cast<std::size_t>(out.laser_of_row[row])] = static_cast<int>(row);
  }
  void add_point(float x, float y, float z, uint8_t, const mrpt::system::TTimeStamp&, const float, uint16_t laser) override {
    const Eigen::Vector3d p(x, y, z);
    const double d = p.norm();
    if (!(d > 0.0) || laser >= row_of_laser_.size()) return;
    // The column: the point's azimuth, clockwise from the sweep's start, over the span.
    double turned = std::fmod(-std::atan2(p.y(), p.x()) - start_, 2 * M_PI);
    if (turned < 0) turned += 2 * M_PI;
    const int cols = out_.range_m.cols;
    const int col = std::clamp(static_cast<int>(std::lround(turned / span_ * cols)), 0, cols - 1);
    const int row = row_of_laser_[laser];
    float& cell = out_.range_m.at<float>(row, col);
    if (cell > 0.0f) {  // taken by an earlier firing
      ++collisions_;
      return;
    }
    cell = static_cast<float>(d);
    const Eigen::Vector3d u = p / d;
    out_.ray.at<cv::Vec3f>(row, col) = cv::Vec3f(static_cast<float>(u.x()), static_cast<float>(u.y()), static_cast<float>(u.z()));
  }
  std::size_t collisions() const { return collisions_; }

 private:
  RangeScan& out_;
  double start_, span_;
  std::vector<int> row_of_laser_;
  std::size_t collisions_ = 0;
};
#pragma GCC diagnostic pop

/// A 3D range scan that holds its points and no range image: a sweep stored by toPointsScan().
const mrpt::obs::CObservation3DRangeScan* pointsOnlyScan(const mrpt::obs::CObservation& observation) {
  const auto* scan = dynamic_cast<const mrpt::obs::CObservation3DRangeScan*>(&observation);
  return scan && !scan->hasRangeImage && scan->hasPoints3D ? scan : nullptr;
}

/// A sweep handed over as its points in the sensor frame: the layout they show (rangeScanFromPoints()).
template <class Vec>
RangeScan sweepFromPoints(const Vec& xs, const Vec& ys, const Vec& zs, const std::string& who,
                          const mrpt::obs::CObservation& observation) {
  std::vector<Eigen::Vector3d> points;
  points.reserve(xs.size());
  for (std::size_t i = 0; i < xs.size() && i < ys.size() && i < zs.size(); ++i) points.emplace_back(xs[i], ys[i], zs[i]);
  RangeScan out = rangeScanFromPoints(points, who);
  out.timestamp = mrpt::Clock::toDouble(observation.timestamp);
  mrpt::poses::CPose3D sensor_pose;
  observation.getSensorPose(sensor_pose);
  out.T_robot_sensor = fromCPose3D(sensor_pose);
  return out;
}

/// An observation of `scan`'s returns, labelled, stamped with its time and its mounting as sensorPose.
template <class Observation>
Observation sweepObservationHead(const RangeScan& scan, const std::string& sensor_label, const std::string& kind) {
  validateLayout(scan, kind + " '" + sensor_label + "'");
  Observation out;
  out.sensorLabel = sensor_label;
  out.timestamp = mrpt::Clock::fromDouble(scan.timestamp);
  out.sensorPose = toCPose3D(scan.T_robot_sensor);
  return out;
}

}  // namespace

RangeScan rangeScanFrom(const mrpt::obs::CObservation& observation) {
  if (const auto* rotating = dynamic_cast<const mrpt::obs::CObservationRotatingScan*>(&observation))
    return rangeScanFrom(*rotating);
  // MRPT 2.5.8's fromGeneric() throws "not implemented" for point clouds: their layout is found here.
  if (const auto* cloud = dynamic_cast<const mrpt::obs::CObservationPointCloud*>(&observation)) {
    const std::string who = "point cloud '" + cloud->sensorLabel + "'";
    if (!cloud->pointcloud && cloud->isExternallyStored()) cloud->load();  // its points in a file beside the rawlog
    if (!cloud->pointcloud) throw Error(who + ": holds no points map");
    return sweepFromPoints(cloud->pointcloud->getPointsBufferRef_x(), cloud->pointcloud->getPointsBufferRef_y(),
                           cloud->pointcloud->getPointsBufferRef_z(), who, observation);
  }
  if (const auto* points = pointsOnlyScan(observation)) {
    if (points->points3D_isExternallyStored()) points->load();  // its points in a file beside the rawlog
    return sweepFromPoints(points->points3D_x, points->points3D_y, points->points3D_z,
                           "3D points scan '" + points->sensorLabel + "'", observation);
  }
  mrpt::obs::CObservationRotatingScan converted;
  if (!converted.fromGeneric(observation))
    throw Error(std::string("observation '") + observation.sensorLabel + "' of class " +
                observation.GetRuntimeClass()->className +
                ": not a range scan GASP reads (rotating, Velodyne, point cloud or 2D)");
  RangeScan out = rangeScanFrom(converted);
  if (const auto* velodyne = dynamic_cast<const mrpt::obs::CObservationVelodyneScan*>(&observation)) {
    // The layout of the conversion, the returns and rays of MRPT's calibrated points.
    if (!(converted.azimuthSpan > 0.0))
      throw Error("Velodyne scan '" + velodyne->sensorLabel + "': its sweep spans no azimuth (too few packets)");
    out.range_m.setTo(0.0f);
    out.ray = cv::Mat::zeros(out.range_m.size(), CV_32FC3);
    CellFiller filler(out, converted.startAzimuth, converted.azimuthSpan);
    mrpt::obs::CObservationVelodyneScan packets = *velodyne;  // generatePointCloud() is not const
    packets.generatePointCloud(filler);
  }
  return out;
}

bool isSweepObservation(const mrpt::obs::CObservation& observation) {
  return dynamic_cast<const mrpt::obs::CObservationRotatingScan*>(&observation) != nullptr ||
         dynamic_cast<const mrpt::obs::CObservationVelodyneScan*>(&observation) != nullptr ||
         dynamic_cast<const mrpt::obs::CObservationPointCloud*>(&observation) != nullptr ||
         pointsOnlyScan(observation) != nullptr;
}

bool isPointsObservation(const mrpt::obs::CObservation& observation) {
  return dynamic_cast<const mrpt::obs::CObservationPointCloud*>(&observation) != nullptr ||
         pointsOnlyScan(observation) != nullptr;
}

std::string observationKind(const mrpt::obs::CObservation& observation) {
  const std::string name = observation.GetRuntimeClass()->className;
  const std::string cls = name.substr(name.rfind(':') == std::string::npos ? 0 : name.rfind(':') + 1);
  if (pointsOnlyScan(observation)) return "a LiDAR sweep as 3D points (" + cls + " without a range image)";
  if (isSweepObservation(observation)) return "a LiDAR sweep (" + cls + ")";
  if (dynamic_cast<const mrpt::obs::CObservation3DRangeScan*>(&observation)) return "a depth image (" + cls + ")";
  return "a " + cls;
}

RgbdFrame sweepFrameFromObservation(const mrpt::obs::CObservation& observation, const std::string& what) {
  if (!isSweepObservation(observation))
    throw Error(what + ": a " + observation.GetRuntimeClass()->className +
                " is not a LiDAR sweep (CObservationRotatingScan, CObservationVelodyneScan, CObservationPointCloud, or "
                "a CObservation3DRangeScan of points without a range image)");
  RgbdFrame frame;
  try {
    frame.sweep = rangeScanFrom(observation);
  } catch (const std::exception& e) {  // gasp::Error (no known elevations, ...) and MRPT's
    throw Error(what + ": " + exceptionMessage(e));
  }
  frame.timestamp = mrpt::Clock::toDouble(observation.timestamp);
  frame.sensor_label = observation.sensorLabel;
  mrpt::poses::CPose3D sensor_pose;
  observation.getSensorPose(sensor_pose);
  frame.T_robot_camera = fromCPose3D(sensor_pose);  // not optical: the LiDAR's own frame
  return frame;
}

mrpt::obs::CObservationRotatingScan toRotatingScan(const RangeScan& scan, const std::string& sensor_label) {
  const int rows = scan.range_m.rows, cols = scan.range_m.cols;
  if (rows == 0 || cols < 2 || scan.range_m.type() != CV_32FC1 || scan.laser_of_row.size() != static_cast<std::size_t>(rows) ||
      scan.azimuth_rad.size() != static_cast<std::size_t>(cols))
    throw Error("range scan '" + sensor_label + "': no layout to write (rows, columns, laser order)");
  if (!scan.ray.empty())
    throw Error("range scan '" + sensor_label + "': its per-return rays cannot be stored in MRPT 2.5's CObservationRotatingScan");
  if (laserElevationsDeg(scan.model, rows).size() != static_cast<std::size_t>(rows))
    throw Error("range scan '" + sensor_label + "': model '" + scan.model + "' is not one whose elevations a reader knows");
  mrpt::obs::CObservationRotatingScan out;
  out.sensorLabel = sensor_label;
  out.timestamp = mrpt::Clock::fromDouble(scan.timestamp);
  out.lidarModel = scan.model;
  out.sensorPose = toCPose3D(scan.T_robot_sensor);
  out.sweepDuration = scan.sweep_duration_s;
  out.rowCount = static_cast<uint16_t>(rows);
  out.columnCount = static_cast<uint16_t>(cols);
  out.rangeResolution = kRotatingScanResolutionM;
  out.minRange = 0.0;
  out.maxRange = 65535 * kRotatingScanResolutionM;
  // The inverse of rangeScanFrom()'s columns: azimuth = sign (start + span c / cols).
  const double sign = turnsClockwise(scan.model) ? -1.0 : 1.0;
  out.startAzimuth = sign * scan.azimuth_rad.front();
  out.azimuthSpan = sign * (scan.azimuth_rad[1] - scan.azimuth_rad[0]) * cols;
  out.rangeImage.setZero(rows, cols);
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      const double d = scan.range_m.at<float>(r, c);
      if (d > 0.0)
        out.rangeImage(scan.laser_of_row[static_cast<std::size_t>(r)], c) =
            static_cast<uint16_t>(std::min(65535.0, std::round(d / kRotatingScanResolutionM)));
    }
  return out;
}

mrpt::obs::CObservationPointCloud toPointCloud(const RangeScan& scan, const std::string& sensor_label) {
  auto out = sweepObservationHead<mrpt::obs::CObservationPointCloud>(scan, sensor_label, "point cloud");
  auto map = mrpt::maps::CSimplePointsMap::Create();
  const std::vector<Eigen::Vector3d> points = scan.points();
  map->reserve(points.size());
  for (const Eigen::Vector3d& p : points)
    map->insertPointFast(static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z()));
  out.pointcloud = map;
  return out;
}

mrpt::obs::CObservation3DRangeScan toPointsScan(const RangeScan& scan, const std::string& sensor_label) {
  auto out = sweepObservationHead<mrpt::obs::CObservation3DRangeScan>(scan, sensor_label, "3D points scan");
  out.hasRangeImage = false;
  out.hasIntensityImage = false;
  const std::vector<Eigen::Vector3d> points = scan.points();
  out.resizePoints3DVectors(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    out.points3D_x[i] = static_cast<float>(points[i].x());
    out.points3D_y[i] = static_cast<float>(points[i].y());
    out.points3D_z[i] = static_cast<float>(points[i].z());
  }
  out.hasPoints3D = true;
  return out;
}

}  // namespace gasp
