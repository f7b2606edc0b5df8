#pragma once
/// \file frame_convention.h The rotation between MRPT's 3D-camera frame and GASP's optical frame.
///
/// MRPT's CObservation3DRangeScan expresses its depth camera with +X forward, +Y left, +Z up;
/// GASP (and TUM, OpenCV) uses the optical frame: x right, y down, z forward. Both share the same
/// origin; they differ by the rotation that MRPT writes as CPose3D(0,0,0, yaw=-90deg, pitch=0,
/// roll=-90deg) (its default relativePoseIntensityWRTDepth for coincident cameras):
///   x_mrpt = z_optical,  y_mrpt = -x_optical,  z_mrpt = -y_optical.
#include "gasp/core/pose.h"

namespace gasp {

/// T_mrpt_optical: maps optical-frame coordinates into MRPT's 3D-camera frame (pure rotation).
Isometry3 mrptCameraFromOptical();

}  // namespace gasp
