#include "gasp/registration/degeneracy.h"

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "gasp/core/error.h"
#include "gasp/core/pose_perturbation.h"

namespace gasp {
namespace {

/// "(x, y, z)" of the unit vector along v, signed so that its largest component is positive.
std::string axisText(const Eigen::Vector3d& v) {
  Eigen::Vector3d u = v.normalized();
  Eigen::Index largest = 0;
  u.cwiseAbs().maxCoeff(&largest);
  if (u(largest) < 0) u = -u;
  for (int i = 0; i < 3; ++i)
    if (std::abs(u(i)) < 0.005) u(i) = 0.0;  // no "-0.00"
  char text[64];
  std::snprintf(text, sizeof text, "(%.2f, %.2f, %.2f)", u.x(), u.y(), u.z());
  return text;
}

/// Names a unit direction [translation; arc] by its larger part, the smaller one when it matters.
std::string directionText(const Vector6d& d) {
  const Eigen::Vector3d t = d.head<3>(), r = d.tail<3>();
  constexpr double kMention = 0.3;
  if (t.norm() >= r.norm())
    return "translation along " + axisText(t) + (r.norm() > kMention ? " with rotation about " + axisText(r) : "");
  return "rotation about " + axisText(r) + (t.norm() > kMention ? " with translation along " + axisText(t) : "");
}

}  // namespace

Matrix6d conditioning(const Eigen::Vector3d& centre, double radius_m) {
  Matrix6d B = Matrix6d::Identity();  // xi = B xi_c: rho = rho_c + c x omega
  B.topRightCorner<3, 3>() = skew(centre);
  Matrix6d S = Matrix6d::Identity();  // omega = arc / L
  S.bottomRightCorner<3, 3>() /= std::max(radius_m, kMinSceneRadiusM);
  return B * S;
}

std::string directionsText(const Eigen::Matrix<double, 6, Eigen::Dynamic>& directions) {
  std::string text;
  for (Eigen::Index j = 0; j < directions.cols(); ++j) text += (j ? "; " : "") + directionText(directions.col(j));
  return text;
}

void validate(const DegeneracyParams& params) {
  if (!(params.min_eigenvalue_ratio >= 0.0 && params.min_eigenvalue_ratio < 1.0))
    throw Error("DegeneracyParams.min_eigenvalue_ratio must be in [0, 1)");
  if (!(params.max_std_m > 0.0)) throw Error("DegeneracyParams.max_std_m must be positive");
}

Matrix6d conditionedInformation(const Matrix6d& information, const Eigen::Vector3d& centre, double radius_m) {
  const Matrix6d BS = conditioning(centre, radius_m);
  const Matrix6d Ic = BS.transpose() * information * BS;
  return 0.5 * (Ic + Ic.transpose());
}

DegeneracyAnalysis analyseDegeneracy(const Matrix6d& information, const Eigen::Vector3d& centre, double radius_m,
                                     const DegeneracyParams& params) {
  validate(params);
  DegeneracyAnalysis out;
  const Eigen::SelfAdjointEigenSolver<Matrix6d> eig(conditionedInformation(information, centre, radius_m));
  out.eigenvalues = eig.eigenvalues();
  const double threshold =
      std::max(params.min_eigenvalue_ratio * out.eigenvalues(5), 1.0 / (params.max_std_m * params.max_std_m));
  int k = 0;
  while (k < 6 && !(out.eigenvalues(k) >= threshold)) ++k;  // NaN counts as unobservable
  if (k == 0) return out;

  // A basis of the unobservable subspace N sorted by rotation content: the SVD of N's rotation
  // rows separates pure translations (null space of those rows) from rotations.
  const Eigen::MatrixXd N = eig.eigenvectors().leftCols(k);
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(N.bottomRows(3), Eigen::ComputeFullV);
  const Eigen::MatrixXd directions = N * svd.matrixV().rowwise().reverse();  // least rotation first
  out.degenerate = true;
  out.unobservable_directions = directions;
  out.unobservable_twists = conditioning(centre, radius_m) * directions;
  out.reason = "unobservable: " + directionsText(directions);
  char ratio[96];
  std::snprintf(ratio, sizeof ratio, " (smallest eigenvalue %.3g, %.3g of the largest)", out.eigenvalues(0),
                out.eigenvalues(5) > 0 ? out.eigenvalues(0) / out.eigenvalues(5) : 0.0);
  out.reason += ratio;
  return out;
}

}  // namespace gasp
