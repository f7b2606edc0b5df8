#include "gasp/baselines/epipolar_rotation.h"

#include <ceres/ceres.h>
#include <ceres/rotation.h>
#include <ceres/sphere_manifold.h>
#include <opencv2/calib3d.hpp>
#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "gasp/baselines/descriptor_matching.h"
#include "gasp/core/error.h"
#include "gasp/core/median.h"

namespace gasp::baselines {

namespace {

/// Sampson distance of one match under E = [t]x R, in normalised image coordinates scaled by
/// `focal` (so the residual is about in pixels). R as an angle-axis correction of R0, t on S^2.
struct SampsonResidual {
  SampsonResidual(const Eigen::Vector3d& x_source, const Eigen::Vector3d& x_target, const Eigen::Matrix3d& R_start,
                  double focal_px)
      : x1(x_source), x2(x_target), R0(R_start), focal(focal_px) {}

  template <typename T>
  bool operator()(const T* const delta, const T* const t, T* residual) const {
    // R = exp(delta) R0: rotate R0 x1 by the correction.
    const Eigen::Matrix<T, 3, 1> r0x1 = (R0 * x1).cast<T>();
    T Rx1[3];
    ceres::AngleAxisRotatePoint(delta, r0x1.data(), Rx1);
    // E x1 = t x (R x1); E^T x2 = R^T (x2 x t)... computed column by column below.
    const Eigen::Matrix<T, 3, 1> tv(t[0], t[1], t[2]);
    const Eigen::Matrix<T, 3, 1> Ex1 = tv.cross(Eigen::Matrix<T, 3, 1>(Rx1[0], Rx1[1], Rx1[2]));
    const Eigen::Matrix<T, 3, 1> x2t = x2.cast<T>();
    const T e = x2t.dot(Ex1);
    // E^T x2 = R^T [t]x^T x2 = -R^T (t x x2) = R^T (x2 x t).
    const Eigen::Matrix<T, 3, 1> x2_cross_t = x2t.cross(tv);
    T minus_delta[3] = {-delta[0], -delta[1], -delta[2]};
    T tmp[3];
    ceres::AngleAxisRotatePoint(minus_delta, x2_cross_t.data(), tmp);
    const Eigen::Matrix<T, 3, 1> Etx2 = R0.transpose().cast<T>() * Eigen::Matrix<T, 3, 1>(tmp[0], tmp[1], tmp[2]);
    const T denom = Ex1[0] * Ex1[0] + Ex1[1] * Ex1[1] + Etx2[0] * Etx2[0] + Etx2[1] * Etx2[1];
    residual[0] = T(focal) * e / ceres::sqrt(denom + T(1e-18));
    return true;
  }

  Eigen::Vector3d x1, x2;
  Eigen::Matrix3d R0;
  double focal;
};


Eigen::Matrix3d toEigen(const cv::Mat& m) {
  Eigen::Matrix3d out;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) out(r, c) = m.at<double>(r, c);
  return out;
}

cv::Mat toGrey(const cv::Mat& image, const CameraIntrinsics& k, const char* which) {
  if (image.empty()) throw Error(std::string("estimateEpipolarRotation: the ") + which + " image is empty");
  if (image.type() != CV_8UC3 && image.type() != CV_8UC1)
    throw Error(std::string("estimateEpipolarRotation: the ") + which + " image must be CV_8UC3 (BGR) or CV_8UC1");
  if (image.cols != k.width || image.rows != k.height)
    throw Error(std::string("estimateEpipolarRotation: the ") + which + " image is " + std::to_string(image.cols) +
                "x" + std::to_string(image.rows) + ", the intrinsics " + std::to_string(k.width) + "x" +
                std::to_string(k.height));
  if (image.type() == CV_8UC1) return image;
  cv::Mat grey;
  cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
  return grey;
}

}  // namespace

void validate(const EpipolarParams& p) {
  if (!(p.contrast_threshold > 0) || !std::isfinite(p.contrast_threshold))
    throw Error("EpipolarParams: contrast_threshold must be > 0 and finite");
  if (!(p.ratio > 0 && p.ratio <= 1)) throw Error("EpipolarParams: ratio must be in (0, 1]");
  if (!(p.threshold_px > 0) || !std::isfinite(p.threshold_px))
    throw Error("EpipolarParams: threshold_px must be > 0 and finite");
  if (!(p.confidence > 0 && p.confidence < 1)) throw Error("EpipolarParams: confidence must be in (0, 1)");
  if (p.max_iterations < 1) throw Error("EpipolarParams: max_iterations must be >= 1");
  if (p.min_inliers < 5) throw Error("EpipolarParams: min_inliers must be >= 5 (the five-point solver)");
  if (!(p.min_parallax_px >= 0) || !std::isfinite(p.min_parallax_px))
    throw Error("EpipolarParams: min_parallax_px must be >= 0 and finite");
}

EpipolarResult estimateEpipolarRotation(const cv::Mat& image_source, const cv::Mat& image_target,
                                        const CameraIntrinsics& k, const EpipolarParams& params) {
  validate(params);
  k.validate();
  const cv::Mat grey_s = toGrey(image_source, k, "source");
  const cv::Mat grey_t = toGrey(image_target, k, "target");
  EpipolarResult out;

  auto sift = cv::SIFT::create(0, 3, params.contrast_threshold);
  std::vector<cv::KeyPoint> kp_s, kp_t;
  cv::Mat d_s, d_t;
  sift->detectAndCompute(grey_s, cv::noArray(), kp_s, d_s);
  sift->detectAndCompute(grey_t, cv::noArray(), kp_t, d_t);
  out.keypoints_source = kp_s.size();
  out.keypoints_target = kp_t.size();
  MatchParams mp;
  mp.ratio = params.ratio;
  const auto matches = kp_s.empty() || kp_t.empty() ? std::vector<DescriptorMatch>{} : matchDescriptors(d_s, d_t, mp);
  out.matches = matches.size();
  if (matches.size() < static_cast<std::size_t>(params.min_inliers)) {
    out.reason = std::to_string(matches.size()) + " SIFT matches, fewer than min_inliers " +
                 std::to_string(params.min_inliers);
    return out;
  }
  std::vector<cv::Point2d> p_s, p_t;
  for (const auto& m : matches) {
    p_s.emplace_back(kp_s[static_cast<std::size_t>(m.a)].pt);
    p_t.emplace_back(kp_t[static_cast<std::size_t>(m.b)].pt);
  }
  {
    // Views that hardly move (the same image) determine no essential matrix.
    std::vector<double> shift;
    for (std::size_t i = 0; i < p_s.size(); ++i) shift.push_back(std::hypot(p_s[i].x - p_t[i].x, p_s[i].y - p_t[i].y));
    const double median_shift = median(std::move(shift));
    if (median_shift < params.min_parallax_px) {
      out.reason = "median displacement of the matches " + std::to_string(median_shift) +
                   " px: no parallax (below min_parallax_px)";
      return out;
    }
  }
  const cv::Mat K = (cv::Mat_<double>(3, 3) << k.fx, 0, k.cx, 0, k.fy, k.cy, 0, 0, 1);
  // OpenCV's RANSAC draws from a generator with a fixed seed of its own: runs repeat.
  cv::Mat mask;
  const cv::Mat E = cv::findEssentialMat(p_s, p_t, K, cv::RANSAC, params.confidence, params.threshold_px,
                                         params.max_iterations, mask);
  if (E.rows != 3 || E.cols != 3) {
    out.reason = "no essential matrix from " + std::to_string(matches.size()) + " matches";
    return out;
  }
  cv::Mat R_cv, t_cv;
  // Cheirality over points up to 1e4 baselines away: the default overload drops points beyond 50
  // baselines, and distant points are the ones that pin the rotation.
  const int good = cv::recoverPose(E, p_s, p_t, K, R_cv, t_cv, 1e4, mask);
  if (good < params.min_inliers) {
    out.reason = std::to_string(good) + " inliers in front of both cameras, fewer than min_inliers " +
                 std::to_string(params.min_inliers);
    out.inliers = static_cast<std::size_t>(std::max(good, 0));
    return out;
  }

  // Polish R and t on every inlier (Sampson distance, Huber loss): the RANSAC model comes from
  // five matches only.
  const Eigen::Matrix3d R0 = toEigen(R_cv);
  double t[3] = {t_cv.at<double>(0), t_cv.at<double>(1), t_cv.at<double>(2)};
  double delta[3] = {0, 0, 0};
  const double focal = 0.5 * (k.fx + k.fy);
  ceres::Problem problem;
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> rays;  // inliers, normalised coordinates
  for (std::size_t i = 0; i < p_s.size(); ++i) {
    if (!mask.at<uchar>(static_cast<int>(i))) continue;
    const Eigen::Vector3d x1((p_s[i].x - k.cx) / k.fx, (p_s[i].y - k.cy) / k.fy, 1.0);
    const Eigen::Vector3d x2((p_t[i].x - k.cx) / k.fx, (p_t[i].y - k.cy) / k.fy, 1.0);
    rays.emplace_back(x1, x2);
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<SampsonResidual, 1, 3, 3>(
                                 new SampsonResidual(x1, x2, R0, focal)),
                             new ceres::HuberLoss(params.threshold_px), delta, t);
  }
  problem.SetManifold(t, new ceres::SphereManifold<3>());
  ceres::Solver::Options options;
  options.max_num_iterations = 50;
  options.num_threads = 1;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  out.inliers = rays.size();
  if (!summary.IsSolutionUsable()) {
    out.reason = "the Sampson refinement failed: " + summary.message;
    return out;
  }
  double Rd[9];
  ceres::AngleAxisToRotationMatrix(delta, Rd);  // column-major
  const Eigen::Matrix3d dR = Eigen::Map<const Eigen::Matrix3d>(Rd);
  const Eigen::Matrix3d R = dR * R0;
  // Parallax: how far each inlier lies from where the rotation alone would take it. Without it
  // the rotation and the translation are not told apart (a rotating camera).
  std::vector<double> parallax;
  for (const auto& [x1, x2] : rays) {
    const Eigen::Vector3d r = R * x1;
    parallax.push_back(std::hypot(k.fx * (x2.x() - r.x() / r.z()), k.fy * (x2.y() - r.y() / r.z())));
  }
  out.median_parallax_px = median(std::move(parallax));
  if (out.median_parallax_px < params.min_parallax_px) {
    out.reason = "median parallax " + std::to_string(out.median_parallax_px) +
                 " px (displacement the rotation does not explain), below min_parallax_px";
    return out;
  }
  out.R_target_source = R;
  out.t_direction = Eigen::Vector3d(t[0], t[1], t[2]).normalized();
  out.success = true;
  return out;
}

}  // namespace gasp::baselines
