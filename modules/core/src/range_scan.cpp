#include "gasp/core/range_scan.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <utility>

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
  range_m = cv::Mat::zeros(static_cast<int>(rows), static_cast<int>(azimuth_rad.size()), CV_32FC1);
  ray.release();
}

}  // namespace gasp
