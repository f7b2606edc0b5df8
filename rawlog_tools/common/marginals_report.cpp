#include "marginals_report.h"

#include <Eigen/Cholesky>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <vector>

#include "gasp/core/error.h"
#include "gasp/eval/pose_consistency.h"

namespace gasp::tools {

namespace {

constexpr double kRadToDeg = 180.0 / M_PI;

/// The q-quantile of v (nearest rank); v is sorted in place, non-empty.
double quantile(std::vector<double>& v, double q) {
  std::sort(v.begin(), v.end());
  const auto k = static_cast<std::size_t>(std::ceil(q * static_cast<double>(v.size())));
  return v[std::min(v.size() - 1, k == 0 ? 0 : k - 1)];
}

}  // namespace

Sigma sigmaOf(const Matrix6d& covariance, const Isometry3& T_world) {
  return {std::sqrt(std::max(0.0, positionCovariance(covariance, T_world).trace())),
          std::sqrt(std::max(0.0, covariance.bottomRightCorner<3, 3>().trace())) * kRadToDeg};
}

void printMarginals(const PoseGraphMarginals& m, const Trajectory& estimate, const Trajectory& gt,
                    const std::string& what) {
  const char* w = what.c_str();
  if (!m.computed) {
    std::printf("marginals: not computed (%s)\n", m.message.c_str());
    return;
  }
  std::size_t known = 0, largest = 0;
  double largest_t = -1.0;
  for (std::size_t i = 0; i < m.covariance.size(); ++i) {
    if (!m.covariance[i]) continue;
    ++known;
    if (i >= estimate.size()) continue;
    const double s = sigmaOf(*m.covariance[i], estimate[i].T_world_camera).t_m;
    if (s > largest_t) largest_t = s, largest = i;
  }
  if (known == 0 || largest_t < 0.0) {
    std::printf("marginals: none (no %s is constrained)\n", w);
    return;
  }
  const Sigma s = sigmaOf(*m.covariance[largest], estimate[largest].T_world_camera);
  std::printf("marginals: %zu %ss (%.1f ms); largest at %s %zu: 1-sigma %.4f m / %.3f deg (relative to %s %zu)\n",
              known, w, m.ms, w, largest, s.t_m, s.r_deg, w, m.piece_root[largest]);
  if (gt.empty()) return;
  std::vector<double> nees;
  for (std::size_t i = 0; i < m.covariance.size() && i < estimate.size(); ++i) {
    const std::size_t root = m.piece_root[i];
    if (!m.covariance[i] || root == i || root >= estimate.size()) continue;
    const auto g = findNearest(gt, estimate[i].timestamp, 0.02);
    const auto g_root = findNearest(gt, estimate[root].timestamp, 0.02);
    if (!g || !g_root) continue;
    const Isometry3 T_ref = estimate[root].T_world_camera * gt[*g_root].T_world_camera.inverse() * gt[*g].T_world_camera;
    const Eigen::LDLT<Matrix6d> ldlt(*m.covariance[i]);
    if (ldlt.info() != Eigen::Success) continue;
    const Matrix6d information = ldlt.solve(Matrix6d::Identity());
    const Matrix6d symmetric = 0.5 * (information + information.transpose());
    try {
      nees.push_back(eval::nees(estimate[i].T_world_camera, T_ref, symmetric));
    } catch (const Error&) {  // a covariance too close to singular to invert: skipped
    }
  }
  if (nees.empty()) {
    std::printf("marginals_nees: no %s with ground truth\n", w);
    return;
  }
  const std::size_t n = nees.size();
  const double q95 = quantile(nees, 0.95), median = quantile(nees, 0.5);
  std::printf("marginals_nees: median %.2f, 95 %% %.2f over %zu %ss (chi-square, 6 degrees of freedom: median %.2f, "
              "95 %% %.2f)\n",
              median, q95, n, w, eval::kChiSquare6Median, eval::kChiSquare6Quantile95);
}

void writeMarginalsCsv(std::ostream& out, const PoseGraphMarginals& m, const Trajectory& estimate) {
  out << "frame,timestamp,root,sigma_t_m,sigma_r_deg";
  for (int r = 0; r < 6; ++r)
    for (int c = 0; c < 6; ++c) out << ",c" << r << c;
  out << '\n';
  for (std::size_t i = 0; i < m.covariance.size() && i < estimate.size(); ++i) {
    if (!m.covariance[i]) continue;
    const Sigma s = sigmaOf(*m.covariance[i], estimate[i].T_world_camera);
    char buf[160];
    std::snprintf(buf, sizeof buf, "%zu,%.6f,%zu,%.6g,%.6g", i, estimate[i].timestamp,
                  m.piece_root[i], s.t_m, s.r_deg);
    out << buf;
    for (int r = 0; r < 6; ++r)
      for (int c = 0; c < 6; ++c) {
        std::snprintf(buf, sizeof buf, ",%.9g", (*m.covariance[i])(r, c));
        out << buf;
      }
    out << '\n';
  }
}

}  // namespace gasp::tools
