#pragma once
/// \file view_projection.h How the pixels of a depth view map to rays in its sensor frame: a
/// pinhole camera (a pixel's value is the depth z along the optical axis) or a spherical range
/// image (rows at laser elevations, columns at evenly spaced azimuths; a cell's value is the range
/// along its ray). The pipeline asks this instead of the pinhole intrinsics, so a rotating LiDAR's
/// sweep is segmented and registered like a depth image.
#include <Eigen/Core>
#include <opencv2/core.hpp>

#include <cmath>
#include <memory>
#include <vector>

#include "gasp/core/camera_intrinsics.h"

namespace gasp {

/// The mean step between ascending elevations [rad] (`one_row` for a single row): a range
/// image's row pitch.
double meanElevationStep(const std::vector<double>& elevation_rad, double one_row);
/// True when `columns` azimuth steps of |step_rad| cover a whole turn (within half a step).
inline bool coversWholeTurn(int columns, double step_rad) {
  return columns * std::abs(step_rad) >= 2.0 * M_PI - 0.5 * std::abs(step_rad);
}

/// `a` wrapped to [-pi, pi] as std::remainder(a, 2 pi) gives it, without that call's cost where it
/// already lies there (a difference of two azimuths in [-pi, pi] mostly does).
inline double wrapToPi(double a) { return std::abs(a) <= M_PI ? a : std::remainder(a, 2.0 * M_PI); }

/// A range image's layout. Sensor frame: x forward, y left, z up (MRPT's LiDAR frame); a ray at
/// elevation e and azimuth a is (cos e cos a, cos e sin a, sin e).
struct SphericalGrid {
  std::vector<double> elevation_rad;  ///< per row, strictly ascending (row 0 is the lowest laser)
  double azimuth_first_rad = 0.0;     ///< of column 0
  double azimuth_step_rad = 0.0;      ///< between columns; negative for a clockwise sweep
  int columns = 0;
  /// Optional CV_32FC3 unit rays per cell (where a sensor's calibration or a binned cell's mean
  /// point is off the nominal direction); empty, or zero at a cell: the nominal ray.
  cv::Mat ray;

  int rows() const { return static_cast<int>(elevation_rad.size()); }
  /// True when the columns cover a whole turn: azimuths wrap around in project().
  bool fullTurn() const { return coversWholeTurn(columns, azimuth_step_rad); }
  /// Mean elevation step between rows [rad] (the step of a one-row grid: the azimuth step).
  double rowPitch() const { return meanElevationStep(elevation_rad, std::abs(azimuth_step_rad)); }
  /// Throws gasp::Error unless rows and columns are 1 to kMaxImageSide, elevations finite, in
  /// [-90, 90] deg and ascending, the azimuth step non-zero and the columns within one turn, and
  /// the ray table empty or CV_32FC3 of the grid's size.
  void validate() const;
};

class ViewProjection {
 public:
  ViewProjection() = default;  ///< CameraIntrinsics' default pinhole
  ViewProjection(const CameraIntrinsics& pinhole)  // NOLINT: implicit, a pinhole is a projection
      : pinhole_(pinhole), area_factor_(static_cast<float>(1.0 / (pinhole.fx * pinhole.fy))) {}
  static ViewProjection spherical(SphericalGrid grid);  ///< validates it

  bool isPinhole() const { return !grid_; }
  /// The pinhole intrinsics; throws gasp::Error for a spherical projection.
  const CameraIntrinsics& pinhole() const;
  /// The range image's layout; throws gasp::Error for a pinhole.
  const SphericalGrid& grid() const;

  int width() const { return grid_ ? grid_->columns : pinhole_.width; }
  int height() const { return grid_ ? grid_->rows() : pinhole_.height; }

  /// The value a pixel holds for point p of the sensor frame: z (pinhole) or |p| (spherical).
  template <typename Vec>
  auto depth(const Vec& p) const {
    return grid_ ? p.norm() : p.z();
  }
  /// Ray of pixel (u, v) scaled so that its point is depth * ray: (x/z, y/z, 1) for a pinhole, the
  /// unit ray of the (nearest) cell for a spherical grid.
  Eigen::Vector3d ray(double u, double v) const;
  /// Point of pixel (u, v) at the given depth (see depth()).
  Eigen::Vector3d unproject(double u, double v, double depth) const {
    if (!grid_) return pinhole_.unproject(u, v, depth);
    return depth * ray(u, v);
  }
  /// Continuous pixel coordinates of p (pixel centres at integers); false when p is behind a
  /// pinhole, at the origin, or outside a spherical grid's rows (half a pitch beyond the end
  /// rows) or columns (unless they cover a turn).
  bool project(const Eigen::Vector3d& p, double& u, double& v) const;

  /// Pixels per radian of view angle (a pinhole's fx; a spherical grid's columns per radian):
  /// how many pixels an object of size s at depth d spans, s / d times this.
  double pixelsPerRadian() const;
  /// Half a pixel's diagonal as a view angle [rad]: how far a point's direction can be from the
  /// centre of the pixel it projects to (a camera's 0.08 deg at fx 525; a 16-laser sweep's binned
  /// cell, 1.4 deg). A surface seen at incidence i spans depth * this / cos(i) across it, and
  /// changes depth by depth * this * tan(i).
  double halfPixelDiagonalRad() const { return 0.5 * std::sqrt(2.0) / pixelsPerRadian(); }
  /// The area [m^2] a pixel sees at point p on a surface facing it: z^2 / (fx fy) for a pinhole,
  /// |p|^2 cos(elevation) * azimuth step * row pitch for a spherical grid.
  float frontalArea(const Eigen::Vector3f& p) const {
    if (!grid_) return p.z() * p.z() * area_factor_;
    return p.norm() * std::sqrt(p.x() * p.x() + p.y() * p.y()) * area_factor_;
  }
  /// The projection of a window of the image: pixel (u, v) of the result is (u0 + u, v0 + v).
  ViewProjection cropped(int u0, int v0, int width, int height) const;

 private:
  CameraIntrinsics pinhole_;
  std::shared_ptr<const SphericalGrid> grid_;  ///< set for a spherical projection
  /// frontalArea()'s constant: 1 / (fx fy), or |azimuth step| * row pitch [sr].
  float area_factor_ = static_cast<float>(1.0 / (525.0 * 525.0));
};

}  // namespace gasp
