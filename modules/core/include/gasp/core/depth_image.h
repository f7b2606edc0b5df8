#pragma once
/// \file depth_image.h Depth images in metres (CV_32FC1; invalid = 0 or NaN) and their uint16 form.
#include <opencv2/core.hpp>
#include <cmath>
#include <cstddef>
#include <string>

namespace gasp {

/// TUM RGB-D (and Kinect OpenNI at 1/5 mm) depth PNGs: raw value / 5000 = metres.
constexpr double kTumDepthUnitsPerMetre = 5000.0;

/// A depth value [m] is valid when it is finite and positive; 0 and NaN both mean "no data".
inline bool isValidDepth(float d) { return std::isfinite(d) && d > 0.0f; }

/// uint16 raw depth (0 = no data) to metres: d = raw / units_per_metre. Throws gasp::Error for a
/// matrix that is not single-channel CV_16U or a non-positive scale.
cv::Mat depthFromRaw(const cv::Mat& raw_u16, double units_per_metre = kTumDepthUnitsPerMetre);

/// Metres to uint16 raw depth, rounded to the nearest unit; invalid or out-of-range values
/// (beyond 65535 units) become 0. Throws gasp::Error for a matrix that is not CV_32FC1.
cv::Mat depthToRaw(const cv::Mat& depth_m, double units_per_metre = kTumDepthUnitsPerMetre);

/// Reads a 16-bit single-channel depth PNG as uint16 raw values. Throws gasp::Error naming the
/// file when it is missing or unreadable, not 16-bit, not single-channel, or (when expected_width
/// and expected_height are positive) of another size.
cv::Mat loadDepthRaw(const std::string& path, int expected_width = 0, int expected_height = 0);

/// loadDepthRaw() converted to metres.
cv::Mat loadDepth(const std::string& path, double units_per_metre = kTumDepthUnitsPerMetre,
                  int expected_width = 0, int expected_height = 0);

/// Writes depth [m] as a 16-bit PNG (depthToRaw()). Throws gasp::Error on failure.
void saveDepth(const std::string& path, const cv::Mat& depth_m,
               double units_per_metre = kTumDepthUnitsPerMetre);

/// Number of valid pixels of a CV_32FC1 depth image.
std::size_t countValidDepth(const cv::Mat& depth_m);

}  // namespace gasp
