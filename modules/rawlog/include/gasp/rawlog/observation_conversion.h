#pragma once
/// \file observation_conversion.h RgbdFrame <-> mrpt::obs::CObservation3DRangeScan.
#include <mrpt/img/TCamera.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/poses/CPose3D.h>

#include "gasp/core/camera_intrinsics.h"
#include "gasp/rawlog/rgbd_frame.h"

namespace gasp {

/// GASP intrinsics to MRPT's TCamera (size, K; distortion k1 k2 p1 p2 k3 with the model set to
/// plumb_bob when any coefficient is non-zero, else DistortionModel::none -- MRPT 2.5 ignores the
/// coefficients of a camera whose model is none).
mrpt::img::TCamera toMrptCamera(const CameraIntrinsics& intrinsics);
/// MRPT's TCamera to GASP intrinsics (plumb_bob coefficients kept; other models -> zeros).
CameraIntrinsics fromMrptCamera(const mrpt::img::TCamera& camera);

/// Eigen isometry <-> CPose3D (same frames, no convention change).
mrpt::poses::CPose3D toCPose3D(const Isometry3& T);
Isometry3 fromCPose3D(const mrpt::poses::CPose3D& pose);

/// Whether frameFromObservation() converts the scan's intensity (colour) image.
enum class ColourImage {
  Convert,  ///< rgb from the intensity image (a missing or damaged image file is an error)
  Skip,     ///< rgb left empty: for what uses depth alone (GASP's registration, odometry, loop
            ///< closure, likelihood), which then neither pays for decoding the image nor fails
            ///< when only the colour image is missing or damaged
};

/// Converts an MRPT 3D range scan to an RgbdFrame.
///  - Loads externally stored data first (obs.load()); relative external files are resolved
///    against mrpt::io::getLazyLoadPathBase() (RawlogReader sets it to "<rawlog>_Images").
///  - range_is_depth = true: depth_raw = rangeImage unchanged, depth_units_per_metre =
///    1 / rangeUnits (snapped to the integer N when the float rangeUnits is the float nearest to
///    1/N, so 1/5000 gives exactly 5000), depth_m = raw / depth_units_per_metre (= depthFromRaw).
///  - range_is_depth = false (ranges along each pixel's ray): converted to depth along the optical
///    axis, depth = range / sqrt(1 + ((u-cx)/fx)^2 + ((v-cy)/fy)^2); depth_raw is left empty.
///  - intensity image (if any, and `colour` is Convert) -> rgb as BGR (grey images are expanded
///    to three channels); rgb_intrinsics from cameraParamsIntensity either way.
///  - sensorPose -> T_robot_camera, relativePoseIntensityWRTDepth -> T_depth_rgb (optical frames).
/// Throws gasp::Error when the scan has no range image, the range image is empty, its size
/// disagrees with cameraParams, or rangeUnits is not positive; `what` names the source (e.g.
/// "file.rawlog, scan 3") for the message.
RgbdFrame frameFromObservation(const mrpt::obs::CObservation3DRangeScan& obs,
                               const std::string& what = "observation", ColourImage colour = ColourImage::Convert);

/// Converts an RgbdFrame to an MRPT 3D range scan.
///  - depth_raw (if present) is stored unchanged with rangeUnits = 1 / depth_units_per_metre;
///    otherwise depth_m is quantised at 1/5000 m (TUM units); range_is_depth = true.
///  - cameraParams / cameraParamsIntensity from the intrinsics incl. distortion.
///  - rgb as intensityImage (CH_VISIBLE) when present.
///  - timestamp via mrpt::Clock::fromDouble, sensorLabel = frame.sensor_label,
///    maxRange = max(10 m, the frame's largest depth), sensorPose and
///    relativePoseIntensityWRTDepth from T_robot_camera and T_depth_rgb.
/// Throws gasp::Error for a missing or mistyped depth image or a size disagreeing with the
/// intrinsics.
mrpt::obs::CObservation3DRangeScan::Ptr observationFromFrame(const RgbdFrame& frame);

/// Stores `obs`'s 3D points in it too (MRPT's unprojection of its range image, in the camera's
/// frame; hasPoints3D set), which MRPT 2.5's points maps need to insert it: they take a scan only
/// from its stored points. About 3.7 MB per 640x480 scan. The range image must be in memory.
void storePoints3D(mrpt::obs::CObservation3DRangeScan& obs);

}  // namespace gasp
