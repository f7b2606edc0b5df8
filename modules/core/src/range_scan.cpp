#include "gasp/core/range_scan.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>
#include <utility>
#include <vector>


#include "gasp/core/error.h"
#include "gasp/core/median.h"
#include "gasp/core/view_projection.h"

namespace gasp {

std::vector<double> laserElevationsDeg(const std::string& lidar_model, int rows) {
  if (lidar_model == "VLP-16") return {-15, 1, -13, 3, -11, 5, -9, 7, -7, 9, -5, 11, -3, 13, -1, 15};
  if (lidar_model == "HDL-32E")
    return {-30.67, -9.33, -29.33, -8.00, -28.00, -6.67, -26.67, -5.33, -25.33, -4.00, -24.00,
            -2.67,  -22.67, -1.33, -21.33, 0.00,  -20.00, 1.33,  -18.67, 2.67,  -17.33, 4.00,
            -16.00, 5.33,  -14.67, 6.67,  -13.33, 8.00,  -12.00, 9.33,  -10.67, 10.67};
  if (lidar_model == "SIM-64") {
    std::vector<double> even;
    for (int i = 0; i < 64; ++i) even.push_back(-24.9 + 26.9 * i / 63.0);
    return even;
  }
  if (lidar_model.rfind("2D_SCAN_", 0) == 0 && rows == 1) return {0.0};
  return {};
}

bool turnsClockwise(const std::string& lidar_model) {
  return lidar_model == "VLP-16" || lidar_model == "HDL-32E" || lidar_model == "SIM-64";
}

Eigen::Vector3d RangeScan::direction(int row, int col) const {
  if (!ray.empty()) {
    const cv::Vec3f& v = ray.at<cv::Vec3f>(row, col);
    if (v[0] != 0.0f || v[1] != 0.0f || v[2] != 0.0f) return {v[0], v[1], v[2]};
  }
  const double el = elevation_rad.at(static_cast<std::size_t>(row)), az = azimuth_rad.at(static_cast<std::size_t>(col));
  return {std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el)};
}

std::vector<Eigen::Vector3d> RangeScan::points() const {
  std::vector<Eigen::Vector3d> out;
  for (int r = 0; r < range_m.rows; ++r)
    for (int c = 0; c < range_m.cols; ++c)
      if (const float d = range_m.at<float>(r, c); d > 0.0f) out.push_back(static_cast<double>(d) * direction(r, c));
  return out;
}

void RangeScan::setLayout(const std::vector<double>& elevation_deg_by_laser, std::vector<double> azimuths_rad) {
  const std::size_t rows = elevation_deg_by_laser.size();
  laser_of_row.resize(rows);
  std::iota(laser_of_row.begin(), laser_of_row.end(), 0);
  std::stable_sort(laser_of_row.begin(), laser_of_row.end(), [&](int a, int b) {
    return elevation_deg_by_laser[static_cast<std::size_t>(a)] < elevation_deg_by_laser[static_cast<std::size_t>(b)];
  });
  elevation_rad.clear();
  for (const int laser : laser_of_row) elevation_rad.push_back(elevation_deg_by_laser[static_cast<std::size_t>(laser)] * M_PI / 180.0);
  azimuth_rad = std::move(azimuths_rad);
  range_m = cv::Mat(static_cast<int>(rows), static_cast<int>(azimuth_rad.size()), CV_32FC1, cv::Scalar(0.0f));  // a new buffer
  ray.release();
}

void validateLayout(const RangeScan& scan, const std::string& who) {
  const int rows = scan.range_m.rows, cols = scan.range_m.cols;
  if (scan.range_m.type() != CV_32FC1 || rows < 1 || cols < 2)
    throw Error(who + ": the range image must be CV_32FC1 with at least one row and two columns");
  if (scan.elevation_rad.size() != static_cast<std::size_t>(rows) || scan.azimuth_rad.size() != static_cast<std::size_t>(cols))
    throw Error(who + ": " + std::to_string(scan.elevation_rad.size()) + " elevations and " +
                std::to_string(scan.azimuth_rad.size()) + " azimuths for a " + std::to_string(rows) + " x " +
                std::to_string(cols) + " range image");
  for (std::size_t i = 0; i < scan.elevation_rad.size(); ++i)
    if (!(std::abs(scan.elevation_rad[i]) <= M_PI / 2) || (i > 0 && !(scan.elevation_rad[i] > scan.elevation_rad[i - 1])))
      throw Error(who + ": the elevations must be within +-90 deg and strictly ascending (row " + std::to_string(i) + ")");
  const double step = std::remainder(scan.azimuth_rad[1] - scan.azimuth_rad[0], 2.0 * M_PI);
  if (!(std::abs(step) > 0.0)) throw Error(who + ": the first two columns have the same azimuth (or one is not finite)");
  for (std::size_t i = 1; i < scan.azimuth_rad.size(); ++i)
    if (!(std::abs(std::remainder(scan.azimuth_rad[i] - scan.azimuth_rad[i - 1], 2.0 * M_PI) - step) <= 0.01 * std::abs(step)))
      throw Error(who + ": the azimuths are not evenly spaced (column " + std::to_string(i) + ")");
  if (!scan.ray.empty() && (scan.ray.type() != CV_32FC3 || scan.ray.rows != rows || scan.ray.cols != cols))
    throw Error(who + ": the ray table must be CV_32FC3 of the range image's size");
}

double azimuthStep(const RangeScan& scan) {
  return wrapToPi(scan.azimuth_rad.at(1) - scan.azimuth_rad.at(0));
}

double rowPitch(const RangeScan& scan) { return meanElevationStep(scan.elevation_rad, std::abs(azimuthStep(scan))); }

int columnsPerRowPitch(const RangeScan& scan) {
  return std::max(1, static_cast<int>(std::lround(rowPitch(scan) / std::abs(azimuthStep(scan)))));
}

bool coversWholeTurn(const RangeScan& scan) { return coversWholeTurn(scan.range_m.cols, azimuthStep(scan)); }

bool nearestCell(const RangeScan& scan, const Eigen::Vector3d& direction, int& row, int& col) {
  // Called for every return a pose maps: plain sqrt (no overflow at a sweep's ranges) and the
  // azimuth step computed once.
  const double horizontal = std::sqrt(direction.x() * direction.x() + direction.y() * direction.y());
  if (!(horizontal > 0.0 || std::abs(direction.z()) > 0.0)) return false;
  const std::vector<double>& E = scan.elevation_rad;
  const double step = azimuthStep(scan);
  const double el = std::atan2(direction.z(), horizontal),
               half_pitch = 0.5 * meanElevationStep(E, std::abs(step));  // half of rowPitch(scan)
  if (!(el >= E.front() - half_pitch && el <= E.back() + half_pitch)) return false;
  const int rows = static_cast<int>(E.size()), cols = scan.range_m.cols;
  int r = static_cast<int>(std::lower_bound(E.begin(), E.end(), el) - E.begin());
  if (r == rows || (r > 0 && el - E[static_cast<std::size_t>(r - 1)] < E[static_cast<std::size_t>(r)] - el)) --r;
  const double turn = 2.0 * M_PI / std::abs(step);  // columns per turn
  double c = wrapToPi(std::atan2(direction.y(), direction.x()) - scan.azimuth_rad[0]) / step;
  if (c < -0.5) c += turn;
  long k = std::lround(c);
  if (coversWholeTurn(cols, step)) {
    k %= cols;  // the few columns past a whole number of them fold onto column 0
    if (k < 0) k += cols;  // c exactly -0.5 rounds to -1
  } else if (k < 0 || k >= cols) {
    return false;
  }
  row = r;
  col = static_cast<int>(k);
  return true;
}

namespace {

/// A point (sensor frame) into the cell nearest its direction with its own ray, unless the cell
/// holds a nearer one (out.ray allocated).
void placeReturn(RangeScan& out, const Eigen::Vector3d& q) {
  const double range = q.norm();
  int row = 0, col = 0;
  if (!(range > 0.0) || !std::isfinite(range) || !nearestCell(out, q, row, col)) return;
  float& cell = out.range_m.at<float>(row, col);
  if (cell > 0.0f && cell <= range) return;
  cell = static_cast<float>(range);
  const Eigen::Vector3f u = (q / range).cast<float>();
  out.ray.at<cv::Vec3f>(row, col) = cv::Vec3f(u.x(), u.y(), u.z());
}

/// The scan's returns moved column by column (T_new_old_of_column(c) for column c's returns), each
/// put in the cell of its new direction (placeReturn). The scan's layout is validated.
template <class TransformOfColumn>
RangeScan rebinned(const RangeScan& scan, TransformOfColumn&& T_new_old_of_column) {
  const int rows = scan.range_m.rows, cols = scan.range_m.cols;
  RangeScan out = scan;
  // New buffers: assigning zeros() to the copied headers would write into the input's images.
  out.range_m = cv::Mat(rows, cols, CV_32FC1, cv::Scalar(0.0f));
  out.ray = cv::Mat(rows, cols, CV_32FC3, cv::Scalar(0.0f, 0.0f, 0.0f));
  std::vector<Isometry3> T(static_cast<std::size_t>(cols));
  for (int c = 0; c < cols; ++c) T[static_cast<std::size_t>(c)] = T_new_old_of_column(c);
  // Row by row: where two returns land in one cell at the same range, the first placed stays.
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      const float d = scan.range_m.at<float>(r, c);
      if (!(d > 0.0f) || !std::isfinite(d)) continue;
      placeReturn(out, T[static_cast<std::size_t>(c)] * (static_cast<double>(d) * scan.direction(r, c)));
    }
  return out;
}

}  // namespace

RangeScan movedScan(const RangeScan& scan, const Isometry3& T_new_old) {
  validateLayout(scan, "movedScan");
  return rebinned(scan, [&](int) { return T_new_old; });
}

double columnTime(const RangeScan& scan, int col) {
  return scan.range_m.cols > 0 ? scan.sweep_duration_s * static_cast<double>(col) / scan.range_m.cols : 0.0;
}

bool sweepTimed(const RangeScan& scan) {
  return scan.sweep_duration_s > 0.0 && std::isfinite(scan.sweep_duration_s) && scan.model != kPointCloudModel;
}

RangeScan deskewSweep(const RangeScan& scan, const CameraTwist& twist) {
  validateLayout(scan, "deskewSweep");
  if (!sweepTimed(scan))
    throw Error("deskewSweep: the sweep's columns carry no firing times (its duration is " +
                std::to_string(scan.sweep_duration_s) + " s" +
                (scan.model == kPointCloudModel ? ", and a point cloud's columns are azimuth bins)" : ")"));
  if (!twist.v_mps.allFinite() || !twist.w_radps.allFinite()) throw Error("deskewSweep: the twist is not finite");
  return rebinned(scan, [&](int c) { return twistMotion(twist, columnTime(scan, c)); });
}

RangeScan rangeScanFromPoints(const std::vector<Eigen::Vector3d>& points_sensor, const std::string& who) {
  std::vector<double> elevation, azimuth;
  for (const Eigen::Vector3d& p : points_sensor)
    if (p.allFinite() && p.norm() > 0.0) {
      elevation.push_back(std::atan2(p.z(), std::hypot(p.x(), p.y())));
      azimuth.push_back(std::atan2(p.y(), p.x()));
    }
  if (elevation.size() < 2) throw Error(who + ": " + std::to_string(elevation.size()) + " points: not a LiDAR's sweep");
  // The rings: the clusters of the sorted elevations.
  std::vector<double> sorted = elevation;
  std::sort(sorted.begin(), sorted.end());
  std::vector<std::vector<double>> clusters(1);
  for (std::size_t i = 0; i < sorted.size(); ++i) {
    if (i > 0 && sorted[i] - sorted[i - 1] > kMinRingGapDeg * M_PI / 180.0) clusters.emplace_back();
    clusters.back().push_back(sorted[i]);
  }
  std::vector<double> rings_deg, widths_deg;  // a ring's median, and its middle 90 %'s spread
  for (const auto& c : clusters)
    if (c.size() >= static_cast<std::size_t>(kMinRingPoints)) {
      rings_deg.push_back(median(c) * 180.0 / M_PI);
      widths_deg.push_back((c[c.size() * 95 / 100] - c[c.size() * 5 / 100]) * 180.0 / M_PI);
    }
  if (rings_deg.size() < 2 || rings_deg.size() > static_cast<std::size_t>(kMaxPointCloudRows))
    throw Error(who + ": the points lie on " + std::to_string(rings_deg.size()) +
                " rings of elevation (2 to " + std::to_string(kMaxPointCloudRows) +
                " expected): not a rotating LiDAR's sweep");
  for (std::size_t r = 0; r < rings_deg.size(); ++r) {
    const double spacing = std::min(r > 0 ? rings_deg[r] - rings_deg[r - 1] : 180.0,
                                    r + 1 < rings_deg.size() ? rings_deg[r + 1] - rings_deg[r] : 180.0);
    if (!(widths_deg[r] < 0.5 * spacing))
      throw Error(who + ": the elevations around " + std::to_string(rings_deg[r]) + " deg spread over " +
                  std::to_string(widths_deg[r]) + " deg, more than half the " + std::to_string(spacing) +
                  " deg to the next ring: not a rotating LiDAR's rings");
  }
  // The azimuth step: per ring (the points nearest its elevation), the median gap between
  // consecutive azimuths; the median over the rings.
  std::vector<std::vector<double>> azimuths(rings_deg.size());
  for (std::size_t i = 0; i < elevation.size(); ++i) {
    const double e = elevation[i] * 180.0 / M_PI;
    std::size_t r = static_cast<std::size_t>(std::lower_bound(rings_deg.begin(), rings_deg.end(), e) - rings_deg.begin());
    if (r == rings_deg.size() || (r > 0 && e - rings_deg[r - 1] < rings_deg[r] - e)) --r;
    azimuths[r].push_back(azimuth[i]);
  }
  std::vector<double> steps;
  for (auto& a : azimuths) {
    std::sort(a.begin(), a.end());
    std::vector<double> gaps;
    for (std::size_t i = 1; i < a.size(); ++i)
      if (a[i] - a[i - 1] > 1e-9) gaps.push_back(a[i] - a[i - 1]);
    if (!gaps.empty()) steps.push_back(median(gaps));
  }
  const double step = steps.empty() ? 0.0 : median(steps);
  if (!(step >= kMinPointCloudColumnDeg * M_PI / 180.0))
    throw Error(who + ": the points' azimuths lie closer than " + std::to_string(kMinPointCloudColumnDeg) +
                " deg apart: not a rotating LiDAR's sweep");
  const int cols = std::max(2, static_cast<int>(std::lround(2.0 * M_PI / step)));
  std::vector<double> columns;
  for (int c = 0; c < cols; ++c) columns.push_back(2.0 * M_PI * c / cols);
  RangeScan out;
  out.model = kPointCloudModel;
  out.setLayout(rings_deg, std::move(columns));
  out.ray = cv::Mat(out.range_m.rows, cols, CV_32FC3, cv::Scalar(0.0f, 0.0f, 0.0f));
  for (const Eigen::Vector3d& p : points_sensor)
    if (p.allFinite()) placeReturn(out, p);
  return out;
}

}  // namespace gasp
