#pragma once
// Helpers of the MRPT-layer tests: real observations as MRPT objects.
#include <gtest/gtest.h>
#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/serialization/CArchive.h>

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "gasp/core/pose.h"
#include "gasp/core/tum_dataset.h"
#include "gasp/rawlog/observation_conversion.h"
#include "gasp/rawlog/tum_to_rawlog.h"

namespace gasp::test {

/// Every CObservation3DRangeScan of a rawlog (format #1 or #2), as MRPT reads it.
inline std::vector<mrpt::obs::CObservation3DRangeScan::Ptr> readScans(const std::string& path) {
  std::vector<mrpt::obs::CObservation3DRangeScan::Ptr> scans;
  mrpt::io::CFileGZInputStream f(path);
  auto in = mrpt::serialization::archiveFrom(f);
  for (;;) {
    mrpt::serialization::CSerializable::Ptr o;
    try {
      in >> o;
    } catch (const std::exception&) {
      break;  // end of file
    }
    if (auto s = std::dynamic_pointer_cast<mrpt::obs::CObservation3DRangeScan>(o)) scans.push_back(s);
    if (auto sf = std::dynamic_pointer_cast<mrpt::obs::CSensoryFrame>(o))
      for (const auto& obs : *sf)
        if (auto s3 = std::dynamic_pointer_cast<mrpt::obs::CObservation3DRangeScan>(obs)) scans.push_back(s3);
  }
  return scans;
}

/// A sensor mount away from the robot origin, so that sensorPose handling is exercised.
inline Isometry3 someMount() {
  Isometry3 S = Isometry3::Identity();
  S.linear() = Eigen::AngleAxisd(0.3, Eigen::Vector3d(0.2, 1.0, 0.1).normalized()).toRotationMatrix();
  S.translation() = Eigen::Vector3d(0.2, -0.1, 0.5);
  return S;
}

/// TUM frame i as an MRPT observation with the given mount, with or without the intensity image.
inline mrpt::obs::CObservation3DRangeScan::Ptr tumObservation(const TumDataset& ds, std::size_t i, bool rgb,
                                                              const Isometry3& T_robot_camera) {
  RgbdFrame f = frameFromTum(ds, i, rgb);
  f.T_robot_camera = T_robot_camera;
  return observationFromFrame(f);
}

}  // namespace gasp::test
