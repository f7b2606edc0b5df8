// The edge information (model_error.h): the refinement's covariance plus the model error,
// inverted; nothing added with zero sigmas; bad input throws.
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include <cmath>
#include <limits>

#include "gasp/core/error.h"
#include "gasp/pipeline/model_error.h"

namespace {

using gasp::Error;
using gasp::informationWithModelError;
using gasp::ModelError;
using Matrix6 = Eigen::Matrix<double, 6, 6>;

/// A correlated information with the scales of a real pair (1e6-1e8: sub-millimetre and
/// hundredths of a degree).
Matrix6 someInformation() {
  Matrix6 A = Matrix6::Identity();
  A(0, 1) = 0.3, A(1, 4) = -0.2, A(2, 5) = 0.1, A(3, 0) = 0.25;
  Eigen::Matrix<double, 6, 1> s;
  s << 2e3, 3e3, 1e3, 5e3, 4e3, 8e3;
  return s.asDiagonal() * (A.transpose() * A) * s.asDiagonal();
}

TEST(ModelError, AddsItsCovarianceToTheRefinementsOwn) {
  const Matrix6 I = someInformation();
  const ModelError e{0.005, 0.5};
  const Matrix6 I_edge = informationWithModelError(I, e);
  Matrix6 expected = I.inverse();
  const double sr = 0.5 * M_PI / 180.0;
  for (int k = 0; k < 3; ++k) expected(k, k) += 0.005 * 0.005, expected(k + 3, k + 3) += sr * sr;
  EXPECT_LT((I_edge.inverse() - expected).norm(), 1e-9 * expected.norm());
  EXPECT_EQ(I_edge, I_edge.transpose());
  // Less certain in every direction, never more: I - I_edge is positive semi-definite.
  const Eigen::SelfAdjointEigenSolver<Matrix6> eig(I - I_edge);
  EXPECT_GE(eig.eigenvalues().minCoeff(), -1e-9 * I.norm());
  // Where the refinement is sure, the model error is what is left: sigma_x ~ 5 mm.
  EXPECT_NEAR(std::sqrt(I_edge.inverse()(0, 0)), 0.005, 2e-4);
  EXPECT_NEAR(std::sqrt(I_edge.inverse()(4, 4)), sr, 1e-5);
}

TEST(ModelError, ZeroSigmasLeaveTheInformationAsItIs) {
  const Matrix6 I = someInformation();
  EXPECT_EQ(informationWithModelError(I, ModelError{0.0, 0.0}), I);
  // Only one of them: the other part keeps the refinement's certainty.
  const Matrix6 t_only = informationWithModelError(I, ModelError{0.005, 0.0});
  EXPECT_LT(std::abs(t_only.inverse()(3, 3) - I.inverse()(3, 3)), 1e-9 * I.inverse()(3, 3));
}

TEST(ModelError, BadInputThrows) {
  const Matrix6 I = someInformation();
  EXPECT_THROW(informationWithModelError(I, ModelError{-0.001, 0.5}), Error);
  EXPECT_THROW(informationWithModelError(I, ModelError{0.005, std::numeric_limits<double>::quiet_NaN()}), Error);
  EXPECT_THROW(informationWithModelError(I, ModelError{0.005, std::numeric_limits<double>::infinity()}), Error);
  EXPECT_THROW(informationWithModelError(I, ModelError{1e155, 1.0}), Error);  // its square would swamp the rest
  EXPECT_THROW(informationWithModelError(I, ModelError{0.01, 200.0}), Error);
  Matrix6 bad = I;
  bad(2, 2) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(informationWithModelError(bad, ModelError{}), Error);
  EXPECT_THROW(informationWithModelError(Matrix6::Zero(), ModelError{}), Error);  // not positive definite
  bad = Matrix6::Identity();
  bad(5, 5) = -1.0;
  EXPECT_THROW(informationWithModelError(bad, ModelError{}), Error);
}

}  // namespace
