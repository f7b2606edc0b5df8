// The analytic point-to-plane cost functions (private plane_residuals.h) against automatic
// differentiation of their templated definitions: values and Jacobians, on unit and non-unit
// quaternions.
#include <gtest/gtest.h>

#include <random>

#include "plane_residuals.h"  // private: this target has modules/registration/src on its path

namespace {

using gasp::detail::SourcePlaneCost;
using gasp::detail::SourcePlaneResidual;
using gasp::detail::TargetPlaneCost;
using gasp::detail::TargetPlaneResidual;

struct Evaluation {
  double r = 0;
  Eigen::Matrix<double, 1, 4> Jq;
  Eigen::Matrix<double, 1, 3> Jt;
};

Evaluation evaluate(const ceres::CostFunction& f, const double* q, const double* t) {
  Evaluation e;
  const double* params[2] = {q, t};
  double* jac[2] = {e.Jq.data(), e.Jt.data()};
  EXPECT_TRUE(f.Evaluate(params, &e.r, jac));
  double r_only = 0;
  EXPECT_TRUE(f.Evaluate(params, &r_only, nullptr));
  EXPECT_NEAR(r_only, e.r, 1e-12);  // automatic differentiation rounds differently with Jets
  return e;
}

void expectSame(const Evaluation& a, const Evaluation& b) {
  EXPECT_NEAR(a.r, b.r, 1e-12);
  EXPECT_LT((a.Jq - b.Jq).cwiseAbs().maxCoeff(), 1e-12) << a.Jq << "\n" << b.Jq;
  EXPECT_LT((a.Jt - b.Jt).cwiseAbs().maxCoeff(), 1e-12) << a.Jt << "\n" << b.Jt;
}

}  // namespace

TEST(PlaneResiduals, AnalyticDerivativesEqualAutomaticOnes) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> g(0.0, 1.0);
  auto vec = [&] { return Eigen::Vector3d(g(rng), g(rng), g(rng)); };
  for (int trial = 0; trial < 500; ++trial) {
    Eigen::Vector4d q(g(rng), g(rng), g(rng), g(rng));
    if (trial % 2 == 0) q.normalize();  // the manifold keeps q unit; the formula holds off it too
    const Eigen::Vector3d t = vec();
    const TargetPlaneResidual tr{vec(), vec(), vec().normalized()};
    const SourcePlaneResidual sr{vec(), vec().normalized(), vec()};
    const ceres::AutoDiffCostFunction<TargetPlaneResidual, 1, 4, 3> auto_t(new TargetPlaneResidual(tr));
    const ceres::AutoDiffCostFunction<SourcePlaneResidual, 1, 4, 3> auto_s(new SourcePlaneResidual(sr));
    expectSame(evaluate(TargetPlaneCost(tr), q.data(), t.data()), evaluate(auto_t, q.data(), t.data()));
    expectSame(evaluate(SourcePlaneCost(sr), q.data(), t.data()), evaluate(auto_s, q.data(), t.data()));
    if (HasFailure()) return;
  }
}

TEST(PlaneResiduals, ValuesAreThePointToPlaneDistances) {
  // 90 deg about z, t = (1, 0, 0): p = (1, 0, 0) maps to (1, 1, 0); the plane z = 0.5 facing +z.
  const Eigen::Quaterniond R(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()));
  const double q[4] = {R.x(), R.y(), R.z(), R.w()};
  const double t[3] = {1.0, 0.0, 0.0};
  const TargetPlaneResidual tr{{1, 0, 0}, {0, 0, 0.5}, {0, 0, 1}};
  EXPECT_NEAR(evaluate(TargetPlaneCost(tr), q, t).r, -0.5, 1e-12);
  const TargetPlaneResidual tx{{1, 0, 0}, {3, 0, 0}, {0, 1, 0}};  // plane y = 0: the point is 1 above
  EXPECT_NEAR(evaluate(TargetPlaneCost(tx), q, t).r, 1.0, 1e-12);
  // Backwards: target point (1, 1, 0) maps to source (1, 0, 0); source plane x = 0.25 facing +x.
  const SourcePlaneResidual sr{{0.25, 0, 0}, {1, 0, 0}, {1, 1, 0}};
  EXPECT_NEAR(evaluate(SourcePlaneCost(sr), q, t).r, 0.75, 1e-12);
}
