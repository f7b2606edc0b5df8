#pragma once
/// \file icp_polish.h An independent check of a relative pose: PCL's Generalized-ICP (Segal,
/// Haehnel, Thrun, RSS 2009) between the two depth clouds, started from a given pose. GASP uses it
/// to judge a *reference* pose (`gasp-pairs --polish-reference`): if GICP started from the
/// ground truth moves far, and to where GASP's estimate is, the reference -- not the estimate --
/// is what disagrees with the depth. It is also the ICP of the benchmark's `gicp` (from the
/// identity) and `gasp-gicp` (from GASP's pose) methods. GICP shares no code or objective with GASP's refinement
/// (plane-to-plane covariances on voxel-sampled clouds, not GASP's patch and projective terms).
#include <opencv2/core.hpp>

#include <cstddef>
#include <string>

#include "gasp/core/camera_intrinsics.h"
#include "gasp/core/pose.h"

namespace gasp::baselines {

struct IcpPolishParams {
  double voxel_m = 0.02;               ///< voxel-grid sampling of both clouds [m]
  double max_depth_m = 4.0;            ///< farther depth is left out [m] (Kinect noise grows with z^2)
  double max_correspondence_m = 0.05;  ///< GICP's correspondence gate [m]
  int max_iterations = 60;             ///< GICP outer iterations
  int min_points = 200;                ///< fewer points in either cloud: no estimate
};

/// Throws gasp::Error naming the first invalid parameter.
void validate(const IcpPolishParams& params);

struct IcpPolishResult {
  bool success = false;  ///< GICP ran from T_init (PCL counts reaching max_iterations as converged)
  Isometry3 T_target_source = Isometry3::Identity();     ///< the polished pose (T_init when !success)
  double fitness_m2 = 0.0;  ///< mean squared distance of source points to their nearest target point, within the gate
  std::size_t source_points = 0, target_points = 0;  ///< after sampling
  std::string reason;  ///< why there is no estimate
};

/// Depth images CV_32FC1 [m] (0 or NaN = no data) of one camera with intrinsics k (validated:
/// type, size, finite pose). T_init maps source-camera points into the target camera.
IcpPolishResult polishPose(const cv::Mat& source_depth_m, const cv::Mat& target_depth_m, const CameraIntrinsics& k,
                           const Isometry3& T_init, const IcpPolishParams& params = {});

}  // namespace gasp::baselines
