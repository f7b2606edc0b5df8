#pragma once
// Test helper: patch correspondences sampled on planes seen from two views, with noise and outliers.
#include <Eigen/Geometry>

#include <cmath>
#include <random>
#include <vector>

#include "gasp/core/pose.h"
#include "gasp/registration/correspondence.h"

namespace gasp::test {

/// A rectangle: centre, unit normal, two in-plane unit axes and half sizes [m].
struct Plane {
  Eigen::Vector3d centre, normal, u, v;
  double half_u, half_v;
};

inline Plane plane(const Eigen::Vector3d& centre, const Eigen::Vector3d& normal, double half_u, double half_v) {
  const Eigen::Vector3d n = normal.normalized();
  const Eigen::Vector3d u = n.unitOrthogonal(), v = n.cross(u);
  return {centre, n, u, v, half_u, half_v};
}

/// A room corner in front of the source camera (optical frame, y down): floor, back wall and
/// left wall, their normals facing the camera.
inline std::vector<Plane> roomCorner() {
  return {plane({0.0, 1.0, 2.5}, {0, -1, 0}, 1.5, 1.5), plane({0.0, 0.0, 4.0}, {0, 0, -1}, 1.5, 1.0),
          plane({-1.5, 0.0, 2.5}, {1, 0, 0}, 1.5, 1.0)};
}

struct SceneOptions {
  int n = 200;
  double outlier_fraction = 0.0;
  double centroid_sigma_m = 0.0;  ///< per axis, in each view
  double normal_sigma_deg = 0.0;  ///< per tangent axis, in each view
  /// Target centroids move by this vector's in-plane component [m, source frame]: patches cut
  /// differently in the two views (e.g. at the image border) slide their centroids along the
  /// surface, a bias centroid fits see and point-to-plane residuals do not.
  Eigen::Vector3d in_plane_bias_m = Eigen::Vector3d::Zero();
  unsigned seed = 7;
};

struct Scene {
  std::vector<PatchCorrespondence> correspondences;
  std::vector<bool> outlier;
};

inline Eigen::Vector3d noisyNormal(const Eigen::Vector3d& n, double sigma_deg, std::mt19937& rng) {
  std::normal_distribution<double> g(0.0, sigma_deg * M_PI / 180.0);
  const Eigen::Vector3d u = n.unitOrthogonal(), v = n.cross(u);
  return (n + g(rng) * u + g(rng) * v).normalized();
}

/// A random patch on a random plane (source frame).
struct Patch {
  Eigen::Vector3d point;
  const Plane* on;
};
inline Patch randomPatch(const std::vector<Plane>& planes, std::mt19937& rng) {
  std::uniform_int_distribution<std::size_t> which(0, planes.size() - 1);
  std::uniform_real_distribution<double> s(-1.0, 1.0);
  const Plane& p = planes[which(rng)];
  return {p.centre + s(rng) * p.half_u * p.u + s(rng) * p.half_v * p.v, &p};
}

/// Correspondences of random patches; the outliers' targets are other random patches.
inline Scene makeScene(const std::vector<Plane>& planes, const Isometry3& T_target_source, const SceneOptions& o) {
  std::mt19937 rng(o.seed);
  std::normal_distribution<double> g(0.0, 1.0);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  auto noise = [&]() -> Eigen::Vector3d { return o.centroid_sigma_m * Eigen::Vector3d(g(rng), g(rng), g(rng)); };
  Scene scene;
  for (int i = 0; i < o.n; ++i) {
    const Patch a = randomPatch(planes, rng);
    const bool outlier = uniform(rng) < o.outlier_fraction;
    const Patch b = outlier ? randomPatch(planes, rng) : a;
    const Eigen::Vector3d shift = o.in_plane_bias_m - b.on->normal.dot(o.in_plane_bias_m) * b.on->normal;
    PatchCorrespondence c;
    c.p_source = a.point + noise();
    c.n_source = noisyNormal(a.on->normal, o.normal_sigma_deg, rng);
    c.p_target = T_target_source * (b.point + shift) + noise();
    c.n_target = noisyNormal(T_target_source.linear() * b.on->normal, o.normal_sigma_deg, rng);
    scene.correspondences.push_back(c);
    scene.outlier.push_back(outlier);
  }
  return scene;
}

/// Rigid motions to test: small, 180-degree roll, 90-degree yaw with a wide baseline, both, random.
inline std::vector<Isometry3> testMotions() {
  using Eigen::AngleAxisd;
  using Eigen::Vector3d;
  std::vector<Isometry3> out;
  out.push_back(Eigen::Translation3d(0.1, -0.05, 0.2) * AngleAxisd(0.15, Vector3d(1, 2, 3).normalized()));
  out.push_back(Eigen::Translation3d(0.3, 0.2, -0.1) * AngleAxisd(M_PI, Vector3d::UnitZ()));
  out.push_back(Eigen::Translation3d(1.5, 0.1, 0.8) * AngleAxisd(M_PI / 2, Vector3d::UnitY()));
  out.push_back(Eigen::Translation3d(-1.2, 0.3, -1.0) * AngleAxisd(M_PI / 2, Vector3d::UnitY()) *
                AngleAxisd(M_PI, Vector3d::UnitZ()));
  std::mt19937 rng(11);
  std::normal_distribution<double> g(0.0, 1.0);
  for (int i = 0; i < 2; ++i) {
    const Eigen::Quaterniond q(g(rng), g(rng), g(rng), g(rng));
    out.push_back(Eigen::Translation3d(g(rng), g(rng), g(rng)) * q.normalized());
  }
  return out;
}

inline double translationError(const Isometry3& a, const Isometry3& b) {
  return (a.translation() - b.translation()).norm();
}
/// Angle of a^-1 b [deg], from the quaternion (acos of the trace loses precision near 0).
inline double rotationErrorDeg(const Isometry3& a, const Isometry3& b) {
  const Eigen::Quaterniond q((a.linear().transpose() * b.linear()).eval());
  return 2.0 * std::atan2(q.vec().norm(), std::abs(q.w())) * 180.0 / M_PI;
}

}  // namespace gasp::test
