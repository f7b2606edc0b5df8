#include "gasp/pipeline/symmetric_turns.h"

#include <Eigen/Eigenvalues>

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

}  // namespace

std::vector<SymmetricTurn> symmetricTurns(const DepthView& source, const DepthView& target,
                                          const Isometry3& T_target_source) {
  std::vector<SymmetricTurn> turns;
  const auto& ps = source.segmentation.patches;
  const auto& pt = target.segmentation.patches;
  if (ps.empty() || pt.empty()) return turns;
  Eigen::Matrix3d S = Eigen::Matrix3d::Zero();
  for (const SurfacePatch& t : pt) S += t.area_m2 * t.normal * t.normal.transpose();
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  double w = 0.0;
  for (const SurfacePatch& s : ps) c += s.area_m2 * (T_target_source * s.centroid), w += s.area_m2;
  if (!(w > 0.0) || !S.allFinite()) return turns;
  c /= w;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(S);
  const Eigen::Matrix3d axes = eig.eigenvectors();
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
