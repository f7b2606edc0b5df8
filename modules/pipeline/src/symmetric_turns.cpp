#include "gasp/pipeline/symmetric_turns.h"

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>

#include <cmath>
#include <map>
#include <utility>

namespace gasp {

namespace {

/// The offset along `axis` of the planes of the patch pairs facing along it in both views (the
/// source turned by R), by 5 cm bins: the fullest bin's mean, or `fallback` without pairs.
double votedOffset(const SuperpixelSegmentation& source, const SuperpixelSegmentation& target, const Eigen::Matrix3d& R,
                   const Eigen::Vector3d& axis, double fallback) {
  const double min_cos = std::cos(10.0 * M_PI / 180.0), bin_m = 0.05;
  std::map<long, std::pair<int, double>> votes;
  for (const SurfacePatch& s : source.patches) {
    const Eigen::Vector3d ns = R * s.normal;
    if (std::abs(ns.dot(axis)) < min_cos) continue;
    const Eigen::Vector3d cs = R * s.centroid;
    for (const SurfacePatch& t : target.patches) {
      if (ns.dot(t.normal) < min_cos) continue;
      const double d = axis.dot(t.centroid - cs);
      auto& v = votes[static_cast<long>(std::floor(d / bin_m))];
      ++v.first;
      v.second += d;
    }
  }
  int best = 0;
  double offset = fallback;
  for (const auto& [bin, v] : votes)
    if (v.first > best) best = v.first, offset = v.second / v.first;
  return offset;
}

/// The area of the patches whose normals lie within `cos_max` of +-`axis`, and their
/// sign-aligned, area-weighted normal sum.
std::pair<double, Eigen::Vector3d> faceAlong(const std::vector<SurfacePatch>& patches, const Eigen::Vector3d& axis,
                                             double cos_max) {
  double area = 0.0;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const SurfacePatch& t : patches) {
    const double c = t.normal.dot(axis);
    if (std::abs(c) < cos_max) continue;
    area += t.area_m2;
    sum += (c < 0.0 ? -t.area_m2 : t.area_m2) * t.normal;
  }
  return {area, sum};
}

}  // namespace

Eigen::Matrix3d sceneAxes(const std::vector<SurfacePatch>& all) {
  const double cos_face = std::cos(20.0 * M_PI / 180.0), sin_face = std::sin(20.0 * M_PI / 180.0);
  std::vector<SurfacePatch> patches;
  for (const SurfacePatch& t : all)
    if (t.normal.allFinite() && std::isfinite(t.area_m2) && t.area_m2 > 0.0) patches.push_back(t);
  Eigen::Matrix3d S = Eigen::Matrix3d::Zero();
  for (const SurfacePatch& t : patches) S += t.area_m2 * t.normal * t.normal.transpose();
  Eigen::Matrix3d axes = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(S).eigenvectors();
  if (!axes.allFinite()) return Eigen::Matrix3d::Identity();
  if (axes.determinant() < 0.0) axes.col(2) = -axes.col(2);  // a rotation
  // The largest face: the patch normal with the most area within 20 deg of it either way.
  double best = 0.0;
  Eigen::Vector3d first = Eigen::Vector3d::Zero();
  for (const SurfacePatch& t : patches) {
    const auto [area, sum] = faceAlong(patches, t.normal, cos_face);
    if (area > best && sum.norm() > 0.0) best = area, first = sum.normalized();
  }
  if (best == 0.0) return axes;
  // The largest face within 20 deg of perpendicular to it (else the principal axis nearest that).
  best = 0.0;
  Eigen::Vector3d second = Eigen::Vector3d::Zero();
  for (const SurfacePatch& t : patches) {
    const Eigen::Vector3d in_plane = t.normal - t.normal.dot(first) * first;
    if (std::abs(t.normal.dot(first)) > sin_face || in_plane.norm() == 0.0) continue;
    const auto [area, sum] = faceAlong(patches, in_plane.normalized(), cos_face);
    const Eigen::Vector3d projected = sum - sum.dot(first) * first;
    if (area > best && projected.norm() > 0.0) best = area, second = projected.normalized();
  }
  if (best == 0.0) {
    int k = 0;
    for (int a = 1; a < 3; ++a)
      if (std::abs(axes.col(a).dot(first)) < std::abs(axes.col(k).dot(first))) k = a;
    second = (axes.col(k) - axes.col(k).dot(first) * first).normalized();
  }
  axes.col(0) = first;
  axes.col(1) = second;
  axes.col(2) = first.cross(second);
  // Refined to the normals within 20 deg of each axis (orthogonal Procrustes), a few times.
  for (int iteration = 0; iteration < 10; ++iteration) {
    Eigen::Matrix3d M = Eigen::Matrix3d::Zero();
    bool supported[3] = {false, false, false};
    for (const SurfacePatch& t : patches) {
      int k = 0;
      for (int a = 1; a < 3; ++a)
        if (std::abs(t.normal.dot(axes.col(a))) > std::abs(t.normal.dot(axes.col(k)))) k = a;
      const double c = t.normal.dot(axes.col(k));
      if (std::abs(c) < cos_face) continue;
      supported[k] = true;
      M += (c < 0.0 ? -t.area_m2 : t.area_m2) * t.normal * Eigen::Vector3d::Unit(k).transpose();
    }
    if (supported[0] + supported[1] + supported[2] < 2) break;  // one face does not fix the others
    const Eigen::JacobiSVD<Eigen::Matrix3d> svd(M, Eigen::ComputeFullU | Eigen::ComputeFullV);
    Eigen::Matrix3d D = Eigen::Matrix3d::Identity();
    D(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0.0 ? -1.0 : 1.0;
    const Eigen::Matrix3d refined = svd.matrixU() * D * svd.matrixV().transpose();
    if (!refined.allFinite()) break;
    const double moved = Eigen::AngleAxisd(refined * axes.transpose()).angle();
    axes = refined;
    if (moved < 1e-4) break;
  }
  return axes;
}

std::vector<SymmetricTurn> symmetricTurns(const DepthView& source, const DepthView& target,
                                          const Isometry3& T_target_source) {
  return symmetricTurns(source, target, T_target_source, sceneAxes(target.segmentation.patches));
}

std::vector<SymmetricTurn> symmetricTurns(const DepthView& source, const DepthView& target,
                                          const Isometry3& T_target_source, const Eigen::Matrix3d& axes) {
  std::vector<SymmetricTurn> turns;
  const auto& ps = source.segmentation.patches;
  const auto& pt = target.segmentation.patches;
  if (ps.empty() || pt.empty()) return turns;
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  double w = 0.0;
  for (const SurfacePatch& s : ps) c += s.area_m2 * (T_target_source * s.centroid), w += s.area_m2;
  if (!(w > 0.0)) return turns;
  c /= w;
  for (int a = 0; a < 3; ++a)
    for (const int degrees : {90, 180, 270}) {
      Isometry3 turn = Isometry3::Identity();
      turn.linear() = Eigen::AngleAxisd(degrees * M_PI / 180.0, axes.col(a)).toRotationMatrix();
      turn.translation() = c - turn.linear() * c;
      SymmetricTurn out;
      out.T_target_source = turn * T_target_source;
      out.axis = axes.col(a);
      out.degrees = degrees;
      // The translation, along each axis, from the planes that face along it.
      const Eigen::Matrix3d R = out.T_target_source.linear();
      Eigen::Vector3d t = Eigen::Vector3d::Zero();
      for (int b = 0; b < 3; ++b)
        t += votedOffset(source.segmentation, target.segmentation, R, axes.col(b),
                         axes.col(b).dot(out.T_target_source.translation())) *
             axes.col(b);
      out.T_target_source.translation() = t;
      turns.push_back(out);
    }
  return turns;
}

}  // namespace gasp
