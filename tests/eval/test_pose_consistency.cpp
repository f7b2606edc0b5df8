// NEES of a pose against a reference: the SE(3) logarithm inverts the exponential, and under
// errors drawn from the claimed information the NEES is chi-square with 6 degrees of freedom.
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "gasp/core/error.h"
#include "gasp/eval/pose_consistency.h"

namespace {

using namespace gasp;
using namespace gasp::eval;

Eigen::Matrix3d hat(const Eigen::Vector3d& w) {
  Eigen::Matrix3d W;
  W << 0, -w.z(), w.y(), w.z(), 0, -w.x(), -w.y(), w.x(), 0;
  return W;
}

/// Exp(xi) for xi = [rho; omega], written out: R = exp(W), t = V rho with
/// V = I + (1 - cos th) / th^2 W + (th - sin th) / th^3 W^2.
Isometry3 expSE3(const Vector6& xi) {
  const Eigen::Vector3d omega = xi.tail<3>();
  const double th = omega.norm();
  Isometry3 T = Isometry3::Identity();
  Eigen::Matrix3d V = Eigen::Matrix3d::Identity();
  if (th > 0) {
    const Eigen::Matrix3d W = hat(omega);
    T.linear() = Eigen::AngleAxisd(th, omega / th).toRotationMatrix();
    V += (1 - std::cos(th)) / (th * th) * W + (th - std::sin(th)) / (th * th * th) * W * W;
  }
  T.translation() = V * xi.head<3>();
  return T;
}

Isometry3 someReference() {
  Isometry3 T = Isometry3::Identity();
  T.linear() = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, -1).normalized()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(0.4, -1.2, 2.0);
  return T;
}

TEST(PoseConsistency, TheLogarithmInvertsTheExponential) {
  const Isometry3 T_ref = someReference();
  std::vector<Vector6> cases;
  Vector6 xi;
  xi << 0.03, -0.02, 0.05, 0.01, -0.02, 0.015;
  cases.push_back(xi);
  xi << 0.5, 1.0, -0.3, 0.0, 0.0, 3.0;  // 172 degrees
  cases.push_back(xi);
  xi << 1e-3, 2e-3, -1e-3, 1e-7, -2e-7, 3e-8;  // below the series threshold
  cases.push_back(xi);
  xi << 0.1, 0.2, 0.3, 0.0, 0.0, 0.0;
  cases.push_back(xi);
  for (const Vector6& x : cases) {
    const Vector6 back = leftPerturbation(expSE3(x) * T_ref, T_ref);
    EXPECT_LT((back - x).norm(), 1e-9 * (1 + x.norm())) << back.transpose() << " vs " << x.transpose();
  }
  EXPECT_LT(leftPerturbation(T_ref, T_ref).norm(), 1e-12);
}

TEST(PoseConsistency, NeesIsChiSquareWithSixDegreesOfFreedomUnderTheClaimedInformation) {
  // An information with very different scales and correlations, as a registration gives.
  Matrix6 A;
  A << 3, 0.5, 0, 0.2, 0, 0, 0, 2, 0.3, 0, 0.1, 0, 0, 0, 1, 0, 0, 0.4, 0.2, 0, 0, 5, 0, 0, 0, 0.3, 0, 0, 4, 0.2, 0,
      0, 0.1, 0, 0, 6;
  const Eigen::Matrix<double, 6, 1> scales = (Eigen::Matrix<double, 6, 1>() << 1e3, 1e3, 3e2, 2e4, 2e4, 1e4).finished();
  const Matrix6 information = scales.asDiagonal() * (A.transpose() * A) * scales.asDiagonal();
  // xi ~ N(0, information^-1): xi = L^-T z with information = L L^T.
  const Eigen::LLT<Matrix6> llt(information);
  ASSERT_EQ(llt.info(), Eigen::Success);
  std::mt19937 rng(7);
  std::normal_distribution<double> g;
  const Isometry3 T_ref = someReference();
  std::vector<double> values;
  double mean_t = 0, mean_r = 0;
  for (int k = 0; k < 4000; ++k) {
    Vector6 z;
    for (int i = 0; i < 6; ++i) z(i) = g(rng);
    const Vector6 xi = llt.matrixU().solve(z);
    const Isometry3 T_est = expSE3(xi) * T_ref;
    values.push_back(nees(T_est, T_ref, information));
    const NeesParts parts = neesParts(T_est, T_ref, information);
    EXPECT_NEAR(parts.all, values.back(), 1e-9 * (1 + values.back()));
    mean_t += parts.translation / 4000, mean_r += parts.rotation / 4000;
  }
  // The parts are chi-square with 3 degrees of freedom: mean 3 (standard error 0.04).
  EXPECT_NEAR(mean_t, 3.0, 0.2);
  EXPECT_NEAR(mean_r, 3.0, 0.2);
  double mean = 0;
  for (double v : values) mean += v / static_cast<double>(values.size());
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  const double median = values[values.size() / 2];
  const auto below95 = std::count_if(values.begin(), values.end(), [](double v) { return v <= kChiSquare6Quantile95; });
  EXPECT_NEAR(mean, 6.0, 0.25);  // standard error sqrt(12 / 4000) = 0.055
  EXPECT_NEAR(median, kChiSquare6Median, 0.3);
  EXPECT_NEAR(static_cast<double>(below95) / static_cast<double>(values.size()), 0.95, 0.015);
}

TEST(PoseConsistency, InvalidInformationThrows) {
  const Isometry3 T = someReference();
  Matrix6 bad = Matrix6::Identity();
  bad(0, 0) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(nees(T, T, bad), Error);
  bad = Matrix6::Identity();
  bad(0, 1) = 0.5;  // not symmetric
  EXPECT_THROW(nees(T, T, bad), Error);
  bad = Matrix6::Identity();
  bad(2, 2) = -1.0;  // not positive semi-definite
  EXPECT_THROW(nees(T, T, bad), Error);
  EXPECT_NO_THROW(nees(T, T, Matrix6::Zero()));
  EXPECT_THROW(neesParts(T, T, Matrix6::Zero()), Error);  // the parts need a covariance
  Matrix6 singular = Matrix6::Identity();
  singular(5, 5) = 0.0;
  EXPECT_THROW(neesParts(T, T, singular), Error);
  EXPECT_LT(nees(T, T, Matrix6::Identity()), 1e-20);
}

}  // namespace
