#include "rigid_fit.h"

#include <Eigen/SVD>

namespace gasp::detail {
namespace {

/// Weights of the listed correspondences, all 1 when they sum to zero.
std::vector<double> weightsOf(const std::vector<PatchCorrespondence>& c, const std::vector<int>& indices) {
  std::vector<double> w;
  double sum = 0.0;
  for (int i : indices) {
    w.push_back(c[i].weight);
    sum += c[i].weight;
  }
  if (!(sum > 0.0)) w.assign(indices.size(), 1.0);
  return w;
}

}  // namespace

Isometry3 fitRigid(const std::vector<PatchCorrespondence>& c, const std::vector<int>& indices) {
  const std::vector<double> w = weightsOf(c, indices);
  double sum = 0.0;
  Eigen::Vector3d mean_s = Eigen::Vector3d::Zero(), mean_t = Eigen::Vector3d::Zero();
  for (std::size_t k = 0; k < indices.size(); ++k) {
    mean_s += w[k] * c[indices[k]].p_source;
    mean_t += w[k] * c[indices[k]].p_target;
    sum += w[k];
  }
  mean_s /= sum;
  mean_t /= sum;
  Eigen::Matrix3d H = Eigen::Matrix3d::Zero();  // sum w (s - mean_s)(t - mean_t)^T
  for (std::size_t k = 0; k < indices.size(); ++k)
    H += w[k] * (c[indices[k]].p_source - mean_s) * (c[indices[k]].p_target - mean_t).transpose();
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(H, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d D = Eigen::Matrix3d::Identity();
  D(2, 2) = (svd.matrixV() * svd.matrixU().transpose()).determinant() < 0.0 ? -1.0 : 1.0;
  Isometry3 T = Isometry3::Identity();
  T.linear() = svd.matrixV() * D * svd.matrixU().transpose();
  T.translation() = mean_t - T.linear() * mean_s;
  return T;
}

}  // namespace gasp::detail
