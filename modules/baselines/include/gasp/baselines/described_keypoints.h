#pragma once
/// \file described_keypoints.h What every baseline's front-end produces for one view: 3D
/// keypoints with normals and one descriptor each, ready for matching (descriptor_matching.h)
/// and for the RANSAC stage (gasp/registration/ransac.h uses points and normals).
#include <Eigen/Core>
#include <opencv2/core.hpp>

#include <vector>

namespace gasp::baselines {

struct DescribedKeypoints {
  std::vector<Eigen::Vector3d> points;   ///< keypoint [m], camera frame (optical)
  std::vector<Eigen::Vector3d> normals;  ///< unit surface normal, facing the camera
  std::vector<cv::Point2f> pixels;       ///< where the keypoint is in the image [px] (pictures)
  cv::Mat descriptors;                   ///< CV_32F, one row per keypoint, finite values
  double describe_ms = 0.0;              ///< wall time of sampling + description [ms]

  std::size_t size() const { return points.size(); }
};

}  // namespace gasp::baselines
