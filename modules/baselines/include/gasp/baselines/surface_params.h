#pragma once
/// \file surface_params.h The downsampled surface every baseline takes 3D points and normals from:
/// the view's valid depth pixels back-projected (pinhole, on images already undistorted as GASP's), reduced by a voxel grid
/// (pcl::VoxelGrid, centroid per voxel; colour averaged), normals by PCA over a radius
/// (pcl::NormalEstimationOMP) oriented towards the camera. FPFH / SHOT use it as their search
/// surface; SIFT keypoints take the normal of the nearest surface point.
namespace gasp::baselines {

struct SurfaceParams {
  double voxel_m = 0.015;         ///< voxel edge of the surface cloud [m]
  double normal_radius_m = 0.03;  ///< neighbourhood radius of a normal [m]
  double max_depth_m = 5.0;       ///< depth beyond this is ignored [m] (Kinect v1 noise grows as z^2)
  int threads = 0;                ///< OpenMP threads for normals and descriptors (0 = all cores)
};

/// Throws gasp::Error naming the first invalid parameter.
void validate(const SurfaceParams& params);

}  // namespace gasp::baselines
