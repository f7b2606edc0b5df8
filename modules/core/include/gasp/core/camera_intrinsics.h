#pragma once
/// \file camera_intrinsics.h Pinhole intrinsics of a depth camera, presets and a text file format.
#include <Eigen/Core>
#include <array>
#include <ostream>
#include <string>

namespace gasp {

/// Pinhole model of a depth camera (optical frame: x right, y down, z forward; metres, pixels).
/// The distortion coefficients (OpenCV order k1 k2 p1 p2 k3) are not applied by unproject() /
/// project(): images are resampled to the pinhole camera first (undistortion.h; TumDataset does
/// it when the coefficients are non-zero).
/// Largest image side accepted [px] (intrinsics files, validate()).
constexpr int kMaxImageSide = 20000;

struct CameraIntrinsics {
  int width = 640;   ///< image width [px]
  int height = 480;  ///< image height [px]
  double fx = 525.0, fy = 525.0;  ///< focal lengths [px]
  double cx = 319.5, cy = 239.5;  ///< principal point [px]
  std::array<double, 5> distortion{};  ///< k1 k2 p1 p2 k3 (see undistortion.h)

  /// 3D point in the camera frame of pixel (u, v) at the given depth [m].
  Eigen::Vector3d unproject(double u, double v, double depth) const {
    return {(u - cx) * depth / fx, (v - cy) * depth / fy, depth};
  }
  /// Pixel coordinates of a point in the camera frame; false when behind the camera.
  bool project(const Eigen::Vector3d& p_camera, double& u, double& v) const;

  /// Throws gasp::Error when a size is not 1 to kMaxImageSide, a focal length not positive and
  /// finite, or the principal point not finite.
  void validate() const;

  static CameraIntrinsics tumFreiburg1();  ///< fx 517.3 fy 516.5 cx 318.6 cy 255.3 (+ distortion)
  static CameraIntrinsics tumFreiburg2();  ///< fx 520.9 fy 521.0 cx 325.1 cy 249.7 (+ distortion)
  static CameraIntrinsics tumFreiburg3();  ///< fx 535.4 fy 539.2 cx 320.1 cy 247.6
  static CameraIntrinsics rosDefault();    ///< fx = fy = 525.0, cx 319.5, cy 239.5

  /// A preset by name: fr1|fr2|fr3|ros (also freiburg1..3); throws gasp::Error otherwise.
  static CameraIntrinsics fromPreset(const std::string& name);
  /// A preset name or, if it is not one, a file in the format of save().
  static CameraIntrinsics fromPresetOrFile(const std::string& preset_or_path);
  /// Reads `key: value` lines (width, height, fx, fy, cx, cy, optional distortion with 5 numbers;
  /// '#' starts a comment). Errors name the file and line.
  static CameraIntrinsics load(const std::string& path);
  /// Writes the format read by load() (whole or not at all: gasp/core/output_file.h).
  void save(const std::string& path) const;
  /// The same into a stream; the caller checks it.
  void save(std::ostream& out) const;
};

bool operator==(const CameraIntrinsics& a, const CameraIntrinsics& b);
inline bool operator!=(const CameraIntrinsics& a, const CameraIntrinsics& b) { return !(a == b); }

}  // namespace gasp
