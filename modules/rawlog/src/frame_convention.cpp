#include "gasp/rawlog/frame_convention.h"

namespace gasp {

Isometry3 mrptCameraFromOptical() {
  Eigen::Matrix3d R_mrpt_optical;
  // Columns: the optical axes x (right), y (down), z (forward) in MRPT's (forward, left, up).
  R_mrpt_optical << 0.0, 0.0, 1.0,   //
      -1.0, 0.0, 0.0,                //
      0.0, -1.0, 0.0;
  Isometry3 T = Isometry3::Identity();
  T.linear() = R_mrpt_optical;
  return T;
}

}  // namespace gasp
