#pragma once
// A synthetic scene segmented as a Kinect would see it, scored against its surfaces (shared by
// the crease and step border tests).
#include <gtest/gtest.h>

#include <utility>

#include "gasp/sim/noise_model.h"
#include "gasp/sim/renderer.h"
#include "gasp/sim/scene.h"
#include "gasp/superpixels/depth_superpixels.h"
#include "segmentation_checks.h"

namespace gasp::test {

/// Pose of an upright rectangle (sim::Rectangle) at `origin`: its x axis along the horizontal
/// `along`, y up (world z), z = along x up.
inline Isometry3 uprightFrame(const Eigen::Vector3d& along, const Eigen::Vector3d& origin) {
  Isometry3 T = Isometry3::Identity();
  T.linear().col(0) = along;
  T.linear().col(1) = Eigen::Vector3d::UnitZ();
  T.linear().col(2) = along.cross(Eigen::Vector3d::UnitZ());
  T.translation() = origin;
  return T;
}

struct ScoredSegmentation {
  SurfacePurity purity;
  SuperpixelSegmentation seg;
};

/// `scene` seen from the world origin along world x (ROS default intrinsics, Kinect noise model,
/// seed 7), segmented with `p`; expects every patch contiguous.
inline ScoredSegmentation segmentNoisyView(const sim::Scene& scene, const SuperpixelParams& p) {
  const auto K = CameraIntrinsics::rosDefault();
  Isometry3 T_world_camera = Isometry3::Identity();  // optical frame: z forward = world x
  T_world_camera.linear() << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  const auto rendered = sim::renderFrame(scene, K, T_world_camera);
  const cv::Mat depth = sim::sensorDepth(rendered, sim::KinectNoiseModel{}, K, 7, 0);
  auto seg = segmentDepthSuperpixels(depth, K, p);
  EXPECT_EQ(countNonContiguousPatches(seg), 0);
  return {surfacePurity(seg, rendered.surface_id), std::move(seg)};
}

}  // namespace gasp::test
