#include "gasp/core/view_projection.h"

#include <algorithm>
#include <string>

#include "gasp/core/error.h"

namespace gasp {

double meanElevationStep(const std::vector<double>& E, double one_row) {
  return E.size() > 1 ? (E.back() - E.front()) / static_cast<double>(E.size() - 1) : one_row;
}

void SphericalGrid::validate() const {
  const int r = rows();
  if (r < 1 || r > kMaxImageSide || columns < 1 || columns > kMaxImageSide)
    throw Error("spherical grid: rows and columns must be from 1 to " + std::to_string(kMaxImageSide) + ", got " +
                std::to_string(r) + " x " + std::to_string(columns));
  for (std::size_t i = 0; i < elevation_rad.size(); ++i) {
    if (!(std::abs(elevation_rad[i]) <= M_PI / 2))
      throw Error("spherical grid: elevation of row " + std::to_string(i) + " is not in [-90, 90] deg");
    if (i > 0 && !(elevation_rad[i] > elevation_rad[i - 1]))
      throw Error("spherical grid: elevations must be strictly ascending (row " + std::to_string(i) + ")");
  }
  if (!std::isfinite(azimuth_first_rad) || !std::isfinite(azimuth_step_rad) || azimuth_step_rad == 0.0)
    throw Error("spherical grid: the azimuth of column 0 must be finite and its step finite and non-zero");
  if (columns * std::abs(azimuth_step_rad) > 2.0 * M_PI + 0.5 * std::abs(azimuth_step_rad))
    throw Error("spherical grid: " + std::to_string(columns) + " columns of " +
                std::to_string(azimuth_step_rad * 180.0 / M_PI) + " deg cover more than one turn");
  if (!ray.empty() && (ray.type() != CV_32FC3 || ray.rows != r || ray.cols != columns))
    throw Error("spherical grid: the ray table must be CV_32FC3 of " + std::to_string(r) + " x " +
                std::to_string(columns));
}

ViewProjection ViewProjection::spherical(SphericalGrid grid) {
  grid.validate();
  if (!grid.ray.empty()) grid.ray = grid.ray.clone();  // its own table: the grid is shared and const
  ViewProjection p;
  p.area_factor_ = static_cast<float>(std::abs(grid.azimuth_step_rad) * grid.rowPitch());
  p.pinhole_.width = grid.columns;
  p.pinhole_.height = grid.rows();
  p.grid_ = std::make_shared<const SphericalGrid>(std::move(grid));
  return p;
}

const CameraIntrinsics& ViewProjection::pinhole() const {
  if (grid_) throw Error("a range image's view has no pinhole intrinsics");
  return pinhole_;
}

const SphericalGrid& ViewProjection::grid() const {
  if (!grid_) throw Error("a pinhole view has no spherical grid");
  return *grid_;
}

Eigen::Vector3d ViewProjection::ray(double u, double v) const {
  if (!grid_) return {(u - pinhole_.cx) / pinhole_.fx, (v - pinhole_.cy) / pinhole_.fy, 1.0};
  const SphericalGrid& g = *grid_;
  const int col = std::clamp(static_cast<int>(std::lround(u)), 0, g.columns - 1);
  const int row = std::clamp(static_cast<int>(std::lround(v)), 0, g.rows() - 1);
  const bool on_cell = std::abs(u - col) < 1e-6 && std::abs(v - row) < 1e-6;
  if (on_cell && !g.ray.empty()) {
    const cv::Vec3f& r = g.ray.at<cv::Vec3f>(row, col);
    if (r[0] != 0.0f || r[1] != 0.0f || r[2] != 0.0f) return {r[0], r[1], r[2]};
  }
  // Elevation interpolated between rows (extrapolated by the end pitch), azimuth linear.
  const int n = g.rows();
  double el;
  if (n == 1) {
    el = g.elevation_rad[0];
  } else {
    const int i = std::clamp(static_cast<int>(std::floor(v)), 0, n - 2);
    el = g.elevation_rad[static_cast<std::size_t>(i)] +
         (v - i) * (g.elevation_rad[static_cast<std::size_t>(i + 1)] - g.elevation_rad[static_cast<std::size_t>(i)]);
  }
  const double az = g.azimuth_first_rad + u * g.azimuth_step_rad;
  return {std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el)};
}

bool ViewProjection::project(const Eigen::Vector3d& p, double& u, double& v) const {
  if (!grid_) return pinhole_.project(p, u, v);
  const SphericalGrid& g = *grid_;
  const double horizontal = std::sqrt(p.x() * p.x() + p.y() * p.y());  // no overflow at a view's depths
  if (!(horizontal > 0.0 || std::abs(p.z()) > 0.0)) return false;
  const double el = std::atan2(p.z(), horizontal);
  const std::vector<double>& E = g.elevation_rad;
  const int n = g.rows();
  const double half_end = 0.5 * g.rowPitch();
  if (n == 1) {
    if (std::abs(el - E[0]) > half_end) return false;
    v = 0.0;
  } else {
    if (el < E.front() - half_end || el > E.back() + half_end) return false;
    const auto it = std::upper_bound(E.begin(), E.end(), el);
    const int i = std::clamp(static_cast<int>(it - E.begin()) - 1, 0, n - 2);
    v = i + (el - E[static_cast<std::size_t>(i)]) / (E[static_cast<std::size_t>(i + 1)] - E[static_cast<std::size_t>(i)]);
  }
  double c = (std::atan2(p.y(), p.x()) - g.azimuth_first_rad) / g.azimuth_step_rad;
  if (g.fullTurn()) {
    const double turn = 2.0 * M_PI / std::abs(g.azimuth_step_rad);  // columns per turn
    c = std::fmod(c, turn);
    if (c < -0.5) c += turn;
    if (c >= turn - 0.5) c -= turn;  // the seam: nearest to column 0
    // A turn of a fractional number of columns: the gap past the last column is no pixel.
    if (c > g.columns - 0.5) return false;
  } else {
    const double turn = 2.0 * M_PI / std::abs(g.azimuth_step_rad);
    // The azimuth difference is known up to whole turns: take the one nearest the grid's middle.
    c -= turn * std::round((c - 0.5 * (g.columns - 1)) / turn);
    if (c < -0.5 || c > g.columns - 0.5) return false;
  }
  u = c;
  return true;
}

double ViewProjection::pixelsPerRadian() const {
  return grid_ ? 1.0 / std::abs(grid_->azimuth_step_rad) : pinhole_.fx;
}

ViewProjection ViewProjection::cropped(int u0, int v0, int width, int height) const {
  if (u0 < 0 || v0 < 0 || width < 1 || height < 1 || u0 + width > this->width() || v0 + height > this->height())
    throw Error("ViewProjection::cropped: the window is not inside the image");
  if (!grid_) {
    ViewProjection p = *this;
    p.pinhole_.width = width, p.pinhole_.height = height, p.pinhole_.cx -= u0, p.pinhole_.cy -= v0;
    return p;
  }
  SphericalGrid g;
  g.elevation_rad.assign(grid_->elevation_rad.begin() + v0, grid_->elevation_rad.begin() + v0 + height);
  g.azimuth_first_rad = grid_->azimuth_first_rad + u0 * grid_->azimuth_step_rad;
  g.azimuth_step_rad = grid_->azimuth_step_rad;
  g.columns = width;
  if (!grid_->ray.empty()) g.ray = grid_->ray(cv::Rect(u0, v0, width, height));
  ViewProjection p = spherical(std::move(g));
  p.area_factor_ = area_factor_;  // the whole grid's row pitch
  return p;
}

}  // namespace gasp
