#pragma once
/// \file point_features.h The paper's geometric baselines with PCL 1.13: FPFH (Rusu et al. 2009),
/// SHOT and colour SHOT (Tombari et al. 2010/2011) on keypoints from volumetric downsampling.
///
/// Keypoints: pcl::UniformSampling of the surface cloud (surface_params.h) -- the surface point
/// nearest each voxel's centre -- with voxel edge keypoint_voxel_m, shrunk by 0.8 until at least
/// min_keypoints are found (the paper: more than 2500 per view) or the surface cloud itself is
/// used. Descriptors (OMP variants) over the whole surface cloud as search surface with its
/// normals: FPFH 33 bins (radius fpfh_radius_m, > the normal radius as PCL requires), SHOT 352
/// (radius shot_radius_m; local reference frame over the same radius), colour SHOT 1344 (SHOT plus
/// the CIELab colour histogram). Keypoints whose descriptor or normal is not finite (too few
/// neighbours, an undefined reference frame) are dropped.
#include <Eigen/Core>

#include <vector>

#include "gasp/baselines/described_keypoints.h"
#include "gasp/baselines/rgbd_image.h"
#include "gasp/baselines/surface_params.h"

namespace gasp::baselines {

enum class PointFeatureType { kFpfh, kShot, kColourShot };

struct PointFeatureParams {
  SurfaceParams surface;           ///< 1.5 cm voxels, normals over 3 cm
  int min_keypoints = 2500;        ///< per view (the paper: > 2500)
  double keypoint_voxel_m = 0.05;  ///< first keypoint voxel edge [m], shrunk by 0.8 as needed
  double fpfh_radius_m = 0.08;     ///< FPFH support radius [m]
  double shot_radius_m = 0.12;     ///< SHOT / colour SHOT support radius [m]
};

/// Throws gasp::Error naming the first invalid parameter.
void validate(const PointFeatureParams& params);

/// Keypoints and descriptors of one view. Throws gasp::Error for an invalid view or parameters,
/// and for colour SHOT on a view without colour. A view without valid depth gives none.
DescribedKeypoints describePointFeatures(const RgbdImage& view, PointFeatureType type,
                                         const PointFeatureParams& params = {});
/// The same on points in a sensor frame (a LiDAR sweep's returns; FPFH or SHOT): keypoint pixels
/// are (-1, -1).
DescribedKeypoints describePointFeatures(const std::vector<Eigen::Vector3f>& points, PointFeatureType type,
                                         const PointFeatureParams& params = {});

}  // namespace gasp::baselines
