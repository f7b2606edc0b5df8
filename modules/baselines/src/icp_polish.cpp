#include "gasp/baselines/icp_polish.h"

#include <pcl/filters/voxel_grid.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/registration/gicp.h>

#include <cmath>

#include "gasp/core/error.h"

namespace gasp::baselines {

namespace {

using Cloud = pcl::PointCloud<pcl::PointXYZ>;

/// Valid depth within max_depth_m, back-projected, then one point (the mean) per voxel.
Cloud::Ptr sampledCloud(const cv::Mat& depth, const CameraIntrinsics& k, const IcpPolishParams& p) {
  Cloud::Ptr raw(new Cloud);
  raw->reserve(depth.total());
  for (int v = 0; v < depth.rows; ++v) {
    const float* d = depth.ptr<float>(v);
    for (int u = 0; u < depth.cols; ++u) {
      const float z = d[u];
      if (!(z > 0.0f) || !(z <= p.max_depth_m)) continue;  // also drops NaN and infinity
      const Eigen::Vector3d q = k.unproject(u, v, z);
      raw->push_back(pcl::PointXYZ(static_cast<float>(q.x()), static_cast<float>(q.y()), static_cast<float>(q.z())));
    }
  }
  Cloud::Ptr out(new Cloud);
  if (raw->empty()) return out;
  pcl::VoxelGrid<pcl::PointXYZ> grid;
  grid.setInputCloud(raw);
  const auto leaf = static_cast<float>(p.voxel_m);
  grid.setLeafSize(leaf, leaf, leaf);
  grid.filter(*out);
  return out;
}

void checkDepth(const cv::Mat& depth, const CameraIntrinsics& k, const char* which) {
  if (depth.type() != CV_32FC1)
    throw Error(std::string("polishPose: ") + which + " depth must be CV_32FC1 [m]");
  if (depth.cols != k.width || depth.rows != k.height)
    throw Error(std::string("polishPose: ") + which + " depth is " + std::to_string(depth.cols) + "x" +
                std::to_string(depth.rows) + ", the intrinsics " + std::to_string(k.width) + "x" +
                std::to_string(k.height));
}

}  // namespace

void validate(const IcpPolishParams& p) {
  if (!(p.voxel_m > 0) || !std::isfinite(p.voxel_m)) throw Error("IcpPolishParams: voxel_m must be finite and > 0");
  if (!(p.max_depth_m > 0)) throw Error("IcpPolishParams: max_depth_m must be > 0");
  if (!(p.max_correspondence_m > 0) || !std::isfinite(p.max_correspondence_m))
    throw Error("IcpPolishParams: max_correspondence_m must be finite and > 0");
  if (p.max_iterations < 1) throw Error("IcpPolishParams: max_iterations must be >= 1");
  if (p.min_points < 3) throw Error("IcpPolishParams: min_points must be >= 3");
}

IcpPolishResult polishPose(const cv::Mat& source_depth_m, const cv::Mat& target_depth_m, const CameraIntrinsics& k,
                           const Isometry3& T_init, const IcpPolishParams& params) {
  validate(params);
  checkDepth(source_depth_m, k, "source");
  checkDepth(target_depth_m, k, "target");
  if (!T_init.matrix().allFinite()) throw Error("polishPose: the initial pose is not finite");
  IcpPolishResult out;
  out.T_target_source = T_init;
  const Cloud::Ptr source = sampledCloud(source_depth_m, k, params);
  const Cloud::Ptr target = sampledCloud(target_depth_m, k, params);
  out.source_points = source->size();
  out.target_points = target->size();
  if (static_cast<int>(std::min(source->size(), target->size())) < params.min_points) {
    out.reason = "too few points after sampling (" + std::to_string(source->size()) + " source, " +
                 std::to_string(target->size()) + " target; min_points " + std::to_string(params.min_points) + ")";
    return out;
  }
  pcl::GeneralizedIterativeClosestPoint<pcl::PointXYZ, pcl::PointXYZ> gicp;
  gicp.setInputSource(source);
  gicp.setInputTarget(target);
  gicp.setMaxCorrespondenceDistance(params.max_correspondence_m);
  gicp.setMaximumIterations(params.max_iterations);
  gicp.setTransformationEpsilon(1e-9);
  Cloud aligned;
  gicp.align(aligned, T_init.matrix().cast<float>());
  if (!gicp.hasConverged()) {
    out.reason = "GICP did not converge";
    return out;
  }
  const Eigen::Matrix4d T = gicp.getFinalTransformation().cast<double>();
  if (!T.allFinite()) {
    out.reason = "GICP returned a non-finite pose";
    return out;
  }
  out.T_target_source.matrix() = T;
  // Re-orthonormalise the rotation (single-precision accumulation in PCL).
  const Eigen::Quaterniond q(out.T_target_source.linear());
  out.T_target_source.linear() = q.normalized().toRotationMatrix();
  out.fitness_m2 = gicp.getFitnessScore(params.max_correspondence_m);
  out.success = true;
  return out;
}

}  // namespace gasp::baselines
