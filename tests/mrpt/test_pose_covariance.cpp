// GASP's information over the left perturbation -> MRPT's covariance over [x y z yaw pitch roll].
#include <gtest/gtest.h>

#include <mrpt/math/wrap2pi.h>

#include <Eigen/Geometry>
#include <limits>
#include <random>

#include "gasp/mrpt/pose_covariance.h"
#include "gasp/rawlog/observation_conversion.h"

using namespace gasp;

namespace {

Isometry3 somePose() {
  Isometry3 T = Isometry3::Identity();
  T.linear() = (Eigen::AngleAxisd(0.8, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(-0.3, Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  T.translation() = Eigen::Vector3d(1.0, -2.0, 0.5);
  return T;
}

Isometry3 exp6(const Eigen::Matrix<double, 6, 1>& xi) {
  Isometry3 D = Isometry3::Identity();
  const Eigen::Vector3d w = xi.tail<3>();
  if (w.norm() > 0) D.linear() = Eigen::AngleAxisd(w.norm(), w.normalized()).toRotationMatrix();
  D.translation() = xi.head<3>();
  return D;
}

}  // namespace

TEST(PoseCovariance, AtTheIdentityYawPitchRollAreTheRotationAboutZYX) {
  Matrix6 cov_xi = Matrix6::Zero();
  cov_xi.diagonal() << 1e-4, 2e-4, 3e-4, 1e-5, 2e-5, 3e-5;  // [t; omega_x omega_y omega_z]
  const auto pdf = poseWithInformation(Isometry3::Identity(), cov_xi.inverse());
  ASSERT_TRUE(pdf);
  EXPECT_NEAR(pdf->cov(0, 0), 1e-4, 1e-12);
  EXPECT_NEAR(pdf->cov(2, 2), 3e-4, 1e-12);
  EXPECT_NEAR(pdf->cov(3, 3), 3e-5, 1e-12);  // yaw   <- omega_z
  EXPECT_NEAR(pdf->cov(4, 4), 2e-5, 1e-12);  // pitch <- omega_y
  EXPECT_NEAR(pdf->cov(5, 5), 1e-5, 1e-12);  // roll  <- omega_x
}

TEST(PoseCovariance, MatchesMonteCarloAtAGeneralPose) {
  const Isometry3 T = somePose();
  Eigen::Matrix<double, 6, 6> A = Eigen::Matrix<double, 6, 6>::Random();
  const Matrix6 cov_xi = 1e-5 * (A * A.transpose() + Matrix6::Identity());
  const auto pdf = poseWithInformation(T, cov_xi.inverse());
  ASSERT_TRUE(pdf);
  const Eigen::LLT<Matrix6> llt(cov_xi);
  std::mt19937 rng(3);
  std::normal_distribution<double> n01;
  const int N = 20000;
  std::vector<Eigen::Matrix<double, 6, 1>> samples;
  Eigen::Matrix<double, 6, 1> mean = Eigen::Matrix<double, 6, 1>::Zero();
  const mrpt::poses::CPose3D m = toCPose3D(T);
  for (int i = 0; i < N; ++i) {
    Eigen::Matrix<double, 6, 1> z;
    for (int k = 0; k < 6; ++k) z[k] = n01(rng);
    const mrpt::poses::CPose3D p = toCPose3D(exp6(llt.matrixL() * z) * T);
    Eigen::Matrix<double, 6, 1> d;
    d << p.x() - m.x(), p.y() - m.y(), p.z() - m.z(), mrpt::math::wrapToPi(p.yaw() - m.yaw()),
        mrpt::math::wrapToPi(p.pitch() - m.pitch()), mrpt::math::wrapToPi(p.roll() - m.roll());
    samples.push_back(d);
    mean += d / N;
  }
  Matrix6 empirical = Matrix6::Zero();
  for (const auto& d : samples) empirical += (d - mean) * (d - mean).transpose() / (N - 1);
  const Matrix6 cov = pdf->cov.asEigen();
  for (int r = 0; r < 6; ++r)
    for (int c = 0; c < 6; ++c)
      EXPECT_NEAR(cov(r, c), empirical(r, c), 0.05 * std::sqrt(cov(r, r) * cov(c, c))) << r << "," << c;
  EXPECT_DOUBLE_EQ(pdf->mean.x(), m.x());
  EXPECT_DOUBLE_EQ(pdf->mean.yaw(), m.yaw());
}

TEST(PoseCovariance, InformationMovesWithTheFrame) {
  // A pose in frame c and the same pose seen from a = S c: sampling in c and mapping to a must
  // give the covariance of the moved information.
  const Isometry3 S = somePose();
  Matrix6 cov_c = Matrix6::Zero();
  cov_c.diagonal() << 1e-4, 4e-4, 9e-4, 1e-5, 4e-5, 9e-5;
  const Matrix6 I_a = informationInFrame(cov_c.inverse(), S);
  // Exp(xi_a) = S Exp(xi_c) S^-1 with xi_a = Ad_S xi_c.
  const Matrix6 Ad = adjoint(S);
  EXPECT_TRUE((Ad * cov_c * Ad.transpose()).isApprox(I_a.inverse(), 1e-9));
  Eigen::Matrix<double, 6, 1> xi;
  xi << 0.01, -0.02, 0.03, 0.002, -0.001, 0.003;
  EXPECT_TRUE((S * exp6(xi) * S.inverse()).isApprox(exp6(Ad * xi), 1e-4));
}

TEST(PoseCovariance, SingularInformationGivesNoCovariance) {
  Matrix6 I = Matrix6::Identity();
  I(2, 2) = 0.0;
  EXPECT_FALSE(poseWithInformation(Isometry3::Identity(), I));
  I(2, 2) = -1.0;
  EXPECT_FALSE(poseWithInformation(Isometry3::Identity(), I));
  I(2, 2) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(poseWithInformation(Isometry3::Identity(), I));
}
