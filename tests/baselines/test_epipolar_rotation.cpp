// estimateEpipolarRotation (SIFT + five-point essential matrix + Sampson polish): on two views
// of the synthetic room painted with a texture fixed to the world, the rotation comes back to
// within a few hundredths of a degree (tested within 0.1: the real disagreements it judges are
// ~1 deg); a camera that only rotates, or does not move, gives no estimate (the translation, and
// with it the split between rotation and translation, is undetermined); bad input gives a clear
// error or no estimate.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>

#include <opencv2/imgproc.hpp>

#include "gasp/baselines/epipolar_rotation.h"
#include "gasp/core/error.h"
#include "gasp/core/pose.h"
#include "gasp/sim/simulation.h"

namespace gb = gasp::baselines;

namespace {

/// Value noise on a 3D lattice of the given cell size [m]: a hash of the cell corners,
/// trilinearly interpolated, in [0, 1].
double valueNoise(const Eigen::Vector3d& p, double cell) {
  const Eigen::Vector3d q = p / cell;
  const Eigen::Vector3d f = q.array().floor();
  const Eigen::Vector3d w = q - f;
  auto corner = [&](int dx, int dy, int dz) {
    std::uint64_t h = static_cast<std::uint64_t>(static_cast<std::int64_t>(f.x()) + dx) * 73856093ULL ^
                      static_cast<std::uint64_t>(static_cast<std::int64_t>(f.y()) + dy) * 19349663ULL ^
                      static_cast<std::uint64_t>(static_cast<std::int64_t>(f.z()) + dz) * 83492791ULL;
    h ^= h >> 33;
    h *= 0xff51afd7ed558ccdULL;
    h ^= h >> 33;
    return static_cast<double>(h % 1000) / 999.0;
  };
  double v = 0.0;
  for (int dx = 0; dx < 2; ++dx)
    for (int dy = 0; dy < 2; ++dy)
      for (int dz = 0; dz < 2; ++dz)
        v += corner(dx, dy, dz) * (dx ? w.x() : 1 - w.x()) * (dy ? w.y() : 1 - w.y()) * (dz ? w.z() : 1 - w.z());
  return v;
}

/// A grey image of frame i of the noise-free room whose every pixel shows the texture of the
/// world point it sees (so two frames show the same texture where they see the same surface).
cv::Mat texturedView(const gasp::sim::Simulation& sim, int i) {
  const auto frame = sim.render(i);
  const auto T = sim.path().poses[static_cast<std::size_t>(i)].T_world_camera;
  const auto& k = sim.options().intrinsics;
  cv::Mat grey(k.height, k.width, CV_8UC1, cv::Scalar(0));
  for (int v = 0; v < k.height; ++v)
    for (int u = 0; u < k.width; ++u) {
      const float z = frame.depth.at<float>(v, u);
      if (!(z > 0)) continue;
      const Eigen::Vector3d p = T * k.unproject(u, v, z);
      const double value = 0.5 * valueNoise(p, 0.09) + 0.3 * valueNoise(p, 0.035) + 0.2 * valueNoise(p, 0.013);
      grey.at<std::uint8_t>(v, u) = static_cast<std::uint8_t>(std::lround(255.0 * value));
    }
  return grey;
}

gasp::sim::Simulation noiseFreeRoom() {
  gasp::sim::SimulationOptions opt;
  opt.scene = "room";
  opt.noise = gasp::sim::KinectNoiseModel::exact();
  return gasp::sim::Simulation(opt);
}

double angleDeg(const Eigen::Matrix3d& A, const Eigen::Matrix3d& B) {
  return std::abs(Eigen::AngleAxisd(A.transpose() * B).angle()) * 180.0 / M_PI;
}

}  // namespace

TEST(EpipolarRotation, RecoversTheRotationOfTwoTexturedViews) {
  const auto sim = noiseFreeRoom();
  for (const auto& [a, b] : {std::pair{3, 9}, std::pair{20, 26}}) {
    const cv::Mat ia = texturedView(sim, a), ib = texturedView(sim, b);
    const gasp::Isometry3 T_b_a = sim.path().poses[static_cast<std::size_t>(b)].T_world_camera.inverse() * sim.path().poses[static_cast<std::size_t>(a)].T_world_camera;
    const auto r = gb::estimateEpipolarRotation(ia, ib, sim.options().intrinsics);
    ASSERT_TRUE(r.success) << a << " -> " << b << ": " << r.reason;
    EXPECT_GT(r.inliers, 200u);
    const double true_angle = angleDeg(Eigen::Matrix3d::Identity(), T_b_a.linear());
    ASSERT_GT(true_angle, 1.0) << "the pair should rotate";
    EXPECT_LT(angleDeg(r.R_target_source, T_b_a.linear()), 0.1) << a << " -> " << b << " (rotates " << true_angle << " deg)";
    std::printf("%d -> %d: rotates %.2f deg, %zu inliers, parallax %.1f px, rotation error %.4f deg\n", a, b, true_angle,
                r.inliers, r.median_parallax_px, angleDeg(r.R_target_source, T_b_a.linear()));
    // The translation direction too (when the views are apart).
    const Eigen::Vector3d t = T_b_a.translation();
    if (t.norm() > 0.05) {
      EXPECT_GT(r.t_direction.dot(t.normalized()), 0.99);
    }
  }
}

TEST(EpipolarRotation, TheSameImageHasNoParallaxAndNoEstimate) {
  const auto sim = noiseFreeRoom();
  const cv::Mat ia = texturedView(sim, 3);
  const auto r = gb::estimateEpipolarRotation(ia, ia, sim.options().intrinsics);
  EXPECT_FALSE(r.success);
  EXPECT_NE(r.reason.find("parallax"), std::string::npos) << r.reason;
}

TEST(EpipolarRotation, APureRotationHasNoParallaxAndNoEstimate) {
  const auto sim = noiseFreeRoom();
  const auto& k = sim.options().intrinsics;
  const cv::Mat ia = texturedView(sim, 3);
  // The image a camera rotated by R about its centre sees: the homography K R K^-1.
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(6.0 * M_PI / 180.0, Eigen::Vector3d(0.2, 1.0, 0.1).normalized()).toRotationMatrix();
  Eigen::Matrix3d K;
  K << k.fx, 0, k.cx, 0, k.fy, k.cy, 0, 0, 1;
  const Eigen::Matrix3d H = K * R * K.inverse();
  cv::Mat Hcv(3, 3, CV_64F);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) Hcv.at<double>(r, c) = H(r, c);
  cv::Mat ib;
  cv::warpPerspective(ia, ib, Hcv, ia.size(), cv::INTER_LINEAR);
  const auto r = gb::estimateEpipolarRotation(ia, ib, k);
  EXPECT_FALSE(r.success) << "claimed a rotation " << angleDeg(r.R_target_source, R) << " deg from the truth";
  EXPECT_NE(r.reason.find("parallax"), std::string::npos) << r.reason;
}

TEST(EpipolarRotation, BadInput) {
  const auto k = gasp::CameraIntrinsics::rosDefault();
  const cv::Mat flat(k.height, k.width, CV_8UC1, cv::Scalar(128));
  // A featureless image: no estimate, with the reason.
  const auto r = gb::estimateEpipolarRotation(flat, flat, k);
  EXPECT_FALSE(r.success);
  EXPECT_NE(r.reason.find("SIFT matches"), std::string::npos) << r.reason;
  EXPECT_THROW(gb::estimateEpipolarRotation(cv::Mat(), flat, k), gasp::Error);
  EXPECT_THROW(gb::estimateEpipolarRotation(flat, cv::Mat(100, 100, CV_8UC1, cv::Scalar(0)), k), gasp::Error);
  EXPECT_THROW(gb::estimateEpipolarRotation(cv::Mat(k.height, k.width, CV_32FC1, cv::Scalar(0)), flat, k), gasp::Error);
  gb::EpipolarParams p;
  p.min_inliers = 4;
  EXPECT_THROW(gb::validate(p), gasp::Error);
  p = {};
  p.threshold_px = std::nan("");
  EXPECT_THROW(gb::validate(p), gasp::Error);
  p = {};
  p.confidence = 1.0;
  EXPECT_THROW(gb::validate(p), gasp::Error);
}
