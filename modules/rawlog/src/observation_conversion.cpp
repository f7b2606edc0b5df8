#include "gasp/rawlog/observation_conversion.h"

#include <mrpt/core/Clock.h>
#include <mrpt/obs/CObservation3DRangeScan_project3D_impl.h>  // unprojectInto
#include <mrpt/img/CImage.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <exception>
#include <fstream>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <string>

#include "gasp/core/depth_image.h"
#include "gasp/core/error.h"
#include "gasp/core/undistortion.h"
#include "gasp/rawlog/frame_convention.h"
#include "gzip_content.h"

namespace gasp {
namespace {

constexpr float kDefaultMaxRangeMetres = 10.0f;

cv::Mat rangeImageToMat(const mrpt::math::CMatrix_u16& range) {
  cv::Mat raw(static_cast<int>(range.rows()), static_cast<int>(range.cols()), CV_16UC1);
  for (int r = 0; r < raw.rows; ++r) {
    auto* row = raw.ptr<std::uint16_t>(r);
    for (int c = 0; c < raw.cols; ++c) row[c] = range(r, c);
  }
  return raw;
}

/// Ranges along each pixel's ray [m] to depth along the optical axis [m]. With lens distortion
/// the ray of pixel (u, v) is the undistorted one (cv::undistortPoints), as MRPT's unprojection
/// has it; the depth image stays on the camera's own (distorted) pixel grid.
cv::Mat rangesToDepth(const cv::Mat& raw, double metres_per_unit, const CameraIntrinsics& K) {
  cv::Mat depth(raw.size(), CV_32FC1);
  std::vector<cv::Point2f> rays;
  if (hasLensDistortion(K)) {
    std::vector<cv::Point2f> pixels;
    pixels.reserve(raw.total());
    for (int v = 0; v < raw.rows; ++v)
      for (int u = 0; u < raw.cols; ++u) pixels.emplace_back(static_cast<float>(u), static_cast<float>(v));
    const cv::Matx33d Km(K.fx, 0.0, K.cx, 0.0, K.fy, K.cy, 0.0, 0.0, 1.0);
    cv::undistortPoints(pixels, rays, Km, cv::Mat(1, 5, CV_64F, const_cast<double*>(K.distortion.data())));
  }
  for (int v = 0; v < raw.rows; ++v) {
    const auto* in = raw.ptr<std::uint16_t>(v);
    auto* out = depth.ptr<float>(v);
    for (int u = 0; u < raw.cols; ++u) {
      double kx = (u - K.cx) / K.fx, ky = (v - K.cy) / K.fy;
      if (!rays.empty()) {
        const cv::Point2f& r = rays[static_cast<std::size_t>(v) * raw.cols + u];
        kx = r.x, ky = r.y;
      }
      out[u] = static_cast<float>(in[u] * metres_per_unit / std::sqrt(1.0 + kx * kx + ky * ky));
    }
  }
  return depth;
}

cv::Mat intensityToBgr(const mrpt::img::CImage& image, const std::string& what) {
  cv::Mat m;
  try {
    image.forceLoad();
    m = image.asCvMat<cv::Mat>(mrpt::img::DEEP_COPY);
  } catch (const std::exception& e) {
    std::string where;
    if (image.isExternallyStored()) where = " (external file " + image.getExternalStorageFileAbsolutePath() + ")";
    throw Error(what + ": cannot load the intensity image" + where + ": " + e.what());
  }
  if (m.empty()) return m;
  if (m.depth() != CV_8U)
    throw Error(what + ": intensity image is not 8-bit (OpenCV type " + std::to_string(m.type()) + ")");
  if (m.channels() == 1) {
    cv::Mat bgr;
    cv::cvtColor(m, bgr, cv::COLOR_GRAY2BGR);
    return bgr;
  }
  if (m.channels() == 4) {
    cv::Mat bgr;
    cv::cvtColor(m, bgr, cv::COLOR_BGRA2BGR);
    return bgr;
  }
  return m;
}

/// 1 / rangeUnits, snapped to the integer N when rangeUnits is the float nearest to 1/N (rangeUnits
/// is a float: 1/5000 is stored as 0.000199999995, whose inverse is 5000.000126).
double unitsPerMetre(float range_units) {
  const double inverse = 1.0 / static_cast<double>(range_units);
  const double rounded = std::round(inverse);
  if (rounded >= 1.0 && static_cast<float>(1.0 / rounded) == range_units) return rounded;
  return inverse;
}

}  // namespace

mrpt::img::TCamera toMrptCamera(const CameraIntrinsics& K) {
  mrpt::img::TCamera cam;
  cam.ncols = static_cast<uint32_t>(K.width);
  cam.nrows = static_cast<uint32_t>(K.height);
  cam.setIntrinsicParamsFromValues(K.fx, K.fy, K.cx, K.cy);
  const auto& d = K.distortion;
  // MRPT 2.5 ignores the coefficients unless the model says plumb_bob.
  if (std::any_of(d.begin(), d.end(), [](double x) { return x != 0.0; }))
    cam.setDistortionPlumbBob(d[0], d[1], d[2], d[3], d[4]);
  else
    cam.distortion = mrpt::img::DistortionModel::none;
  return cam;
}

CameraIntrinsics fromMrptCamera(const mrpt::img::TCamera& cam) {
  CameraIntrinsics K;
  K.width = static_cast<int>(cam.ncols);
  K.height = static_cast<int>(cam.nrows);
  K.fx = cam.fx();
  K.fy = cam.fy();
  K.cx = cam.cx();
  K.cy = cam.cy();
  // Only the pin-hole (plumb_bob) coefficients map onto GASP's k1 k2 p1 p2 k3.
  if (cam.distortion == mrpt::img::DistortionModel::plumb_bob)
    K.distortion = {cam.k1(), cam.k2(), cam.p1(), cam.p2(), cam.k3()};
  return K;
}

mrpt::poses::CPose3D toCPose3D(const Isometry3& T) {
  return mrpt::poses::CPose3D::FromHomogeneousMatrix(mrpt::math::CMatrixDouble44(T.matrix()));
}

Isometry3 fromCPose3D(const mrpt::poses::CPose3D& pose) {
  Isometry3 T = Isometry3::Identity();
  T.matrix() = pose.getHomogeneousMatrixVal<mrpt::math::CMatrixDouble44>().asEigen();
  return T;
}

RgbdFrame frameFromObservation(const mrpt::obs::CObservation3DRangeScan& obs, const std::string& what,
                               ColourImage colour) {
  if (!obs.hasRangeImage)
    throw Error(what + ": CObservation3DRangeScan '" + obs.sensorLabel +
                "' has no range image (hasRangeImage = false); GASP needs depth");
  if (obs.rangeImage_isExternallyStored()) {
    // MRPT loads what it can of a cut or damaged file. The gzip stream must be whole; in MRPT 2's
    // .bin layout (rows, cols as uint32, then the uint16 values) the size must be the camera's and
    // all rows x cols values must be there. Other files (`rawlog-edit --txt-externals` text) are
    // left to MRPT.
    const std::string file = obs.rangeImage_getExternalStorageFileAbsolutePath("");
    if (std::ifstream(file).good()) {
      const auto content = detail::readGzipContent(file, what + ": external range image", 8);
      std::uint32_t rows = 0, cols = 0;
      if (content.head.size() == 8) {
        std::memcpy(&rows, content.head.data(), 4);
        std::memcpy(&cols, content.head.data() + 4, 4);
      }
      const bool mrpt2_layout = rows == obs.cameraParams.nrows && cols == obs.cameraParams.ncols;
      if (mrpt2_layout && content.length != 8 + 2ull * rows * cols)
        throw Error(what + ": external range image '" + file + "' is cut or damaged: " + std::to_string(content.length) +
                    " bytes for a " + std::to_string(rows) + " x " + std::to_string(cols) + " image");
      // MRPT 2.5.8 reads a .bin file's first 8 bytes as the image size and allocates it before
      // reading anything else: a damaged header crashes it (garbage sizes overflow its int
      // arithmetic). A .bin whose header is not the camera's size is refused here.
      const bool bin = file.size() >= 4 && file.compare(file.size() - 4, 4, ".bin") == 0;
      if (bin && !mrpt2_layout)
        throw Error(what + ": external range image '" + file + "' is damaged or not this scan's: " +
                    (content.head.size() < 8 ? "shorter than its 8-byte size header"
                                             : "its header gives " + std::to_string(rows) + " x " + std::to_string(cols) +
                                                   " pixels, the camera " + std::to_string(obs.cameraParams.nrows) +
                                                   " x " + std::to_string(obs.cameraParams.ncols)));
    }
  }
  try {
    obs.load();
  } catch (const std::exception& e) {
    std::string where;
    if (obs.rangeImage_isExternallyStored())
      where = " (external file " + obs.rangeImage_getExternalStorageFileAbsolutePath("") + ")";
    throw Error(what + ": cannot load the externally stored data" + where + ": " + e.what());
  }
  if (obs.rangeImage.rows() == 0 || obs.rangeImage.cols() == 0)
    throw Error(what + ": the range image is empty (0 x 0)");
  if (!(obs.rangeUnits > 0.0f) || !std::isfinite(obs.rangeUnits))
    throw Error(what + ": rangeUnits must be positive, got " + std::to_string(obs.rangeUnits));

  RgbdFrame f;
  f.timestamp = mrpt::Clock::toDouble(obs.timestamp);
  f.sensor_label = obs.sensorLabel;
  f.depth_intrinsics = fromMrptCamera(obs.cameraParams);
  const int w = static_cast<int>(obs.rangeImage.cols());
  const int h = static_cast<int>(obs.rangeImage.rows());
  if (f.depth_intrinsics.width != w || f.depth_intrinsics.height != h)
    throw Error(what + ": range image is " + std::to_string(w) + "x" + std::to_string(h) +
                " but cameraParams say " + std::to_string(f.depth_intrinsics.width) + "x" +
                std::to_string(f.depth_intrinsics.height));
  try {
    f.depth_intrinsics.validate();
  } catch (const Error& e) {
    throw Error(what + ": cameraParams: " + e.what());
  }

  const cv::Mat raw = rangeImageToMat(obs.rangeImage);
  const double units_per_metre = unitsPerMetre(obs.rangeUnits);
  const double metres_per_unit = 1.0 / units_per_metre;
  if (obs.range_is_depth) {
    f.depth_raw = raw;
    f.depth_units_per_metre = units_per_metre;
    f.depth_m = depthFromRaw(raw, units_per_metre);
  } else {
    f.depth_m = rangesToDepth(raw, metres_per_unit, f.depth_intrinsics);
  }

  if (obs.hasIntensityImage) {
    f.rgb_intrinsics = fromMrptCamera(obs.cameraParamsIntensity);
    if (colour == ColourImage::Convert) f.rgb = intensityToBgr(obs.intensityImage, what);
    if (!f.rgb.empty() && (f.rgb.cols != f.rgb_intrinsics.width || f.rgb.rows != f.rgb_intrinsics.height))
      throw Error(what + ": intensity image is " + std::to_string(f.rgb.cols) + "x" + std::to_string(f.rgb.rows) +
                  " but cameraParamsIntensity say " + std::to_string(f.rgb_intrinsics.width) + "x" +
                  std::to_string(f.rgb_intrinsics.height));
  }
  // A pose with NaN would compare unequal to itself ("another sensorPose than the first").
  for (const auto* pose : {&obs.sensorPose, &obs.relativePoseIntensityWRTDepth}) {
    // The matrix held here: asEigen() of the temporary would map memory freed at the end of
    // the statement (ASan: stack-use-after-scope, found by fuzz_rawlog).
    const auto matrix = pose->getHomogeneousMatrixVal<mrpt::math::CMatrixDouble44>();
    const auto m = matrix.asEigen();
    if (!m.allFinite() || m.block<3, 1>(0, 3).cwiseAbs().maxCoeff() > 1e8)
      throw Error(what + ": " + (pose == &obs.sensorPose ? "sensorPose" : "relativePoseIntensityWRTDepth") +
                  " is not finite or beyond 1e8 m");
  }
  const Isometry3 T_mrpt_optical = mrptCameraFromOptical();
  f.T_depth_rgb = T_mrpt_optical.inverse() * fromCPose3D(obs.relativePoseIntensityWRTDepth);
  f.T_robot_camera = fromCPose3D(obs.sensorPose) * T_mrpt_optical;
  return f;
}

mrpt::obs::CObservation3DRangeScan::Ptr observationFromFrame(const RgbdFrame& frame) {
  cv::Mat raw;
  double units_per_metre = kTumDepthUnitsPerMetre;
  if (frame.hasRawDepth()) {
    if (frame.depth_raw.type() != CV_16UC1) throw Error("RgbdFrame: depth_raw must be CV_16UC1");
    raw = frame.depth_raw;
    units_per_metre = frame.depth_units_per_metre;
  } else {
    if (frame.depth_m.empty()) throw Error("RgbdFrame: no depth (depth_m and depth_raw empty)");
    raw = depthToRaw(frame.depth_m, units_per_metre);
  }
  const CameraIntrinsics& K = frame.depth_intrinsics;
  K.validate();
  if (raw.cols != K.width || raw.rows != K.height)
    throw Error("RgbdFrame: depth is " + std::to_string(raw.cols) + "x" + std::to_string(raw.rows) +
                " but the depth intrinsics say " + std::to_string(K.width) + "x" +
                std::to_string(K.height));

  auto obs = mrpt::obs::CObservation3DRangeScan::Create();
  obs->timestamp = mrpt::Clock::fromDouble(frame.timestamp);
  obs->sensorLabel = frame.sensor_label;
  obs->hasRangeImage = true;
  obs->range_is_depth = true;
  obs->rangeUnits = static_cast<float>(1.0 / units_per_metre);
  obs->rangeImage_setSize(raw.rows, raw.cols);
  std::uint16_t max_raw = 0;
  for (int r = 0; r < raw.rows; ++r) {
    const auto* row = raw.ptr<std::uint16_t>(r);
    for (int c = 0; c < raw.cols; ++c) {
      obs->rangeImage(r, c) = row[c];
      max_raw = std::max(max_raw, row[c]);
    }
  }
  obs->maxRange = std::max(kDefaultMaxRangeMetres, static_cast<float>(max_raw / units_per_metre));
  obs->cameraParams = toMrptCamera(K);
  obs->cameraParams.cameraName = frame.sensor_label + "_depth";

  if (frame.hasRgb()) {
    if (frame.rgb.type() != CV_8UC3) throw Error("RgbdFrame: rgb must be CV_8UC3 (BGR)");
    frame.rgb_intrinsics.validate();
    if (frame.rgb.cols != frame.rgb_intrinsics.width || frame.rgb.rows != frame.rgb_intrinsics.height)
      throw Error("RgbdFrame: rgb is " + std::to_string(frame.rgb.cols) + "x" +
                  std::to_string(frame.rgb.rows) + " but the rgb intrinsics say " +
                  std::to_string(frame.rgb_intrinsics.width) + "x" +
                  std::to_string(frame.rgb_intrinsics.height));
    obs->hasIntensityImage = true;
    obs->intensityImage = mrpt::img::CImage(frame.rgb, mrpt::img::DEEP_COPY);
    obs->intensityImageChannel = mrpt::obs::CObservation3DRangeScan::CH_VISIBLE;
    obs->cameraParamsIntensity = toMrptCamera(frame.rgb_intrinsics);
  } else {
    obs->cameraParamsIntensity = toMrptCamera(K);
  }
  obs->cameraParamsIntensity.cameraName = frame.sensor_label + "_rgb";

  const Isometry3 T_mrpt_optical = mrptCameraFromOptical();
  obs->relativePoseIntensityWRTDepth = toCPose3D(T_mrpt_optical * frame.T_depth_rgb);
  obs->sensorPose = toCPose3D(frame.T_robot_camera * T_mrpt_optical.inverse());
  return obs;
}

void storePoints3D(mrpt::obs::CObservation3DRangeScan& obs) { obs.unprojectInto(obs); }

}  // namespace gasp
