// Marginal covariances of a pose graph (pose_graph_marginals.h) against answers known without
// Ceres: the first-order composition along a chain, two edges in parallel, and (J^T J)^-1 by
// numerical differentiation of the edges' whitened residuals on a graph with loops.
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include <cmath>
#include <random>
#include <vector>

#include "gasp/core/error.h"
#include "gasp/slam/pose_graph.h"
#include "gasp/slam/pose_graph_marginals.h"
#include "gasp/slam/pose_graph_optimizer.h"

namespace {

using gasp::Isometry3;
using gasp::Matrix6d;
using gasp::PoseConstraint;
using gasp::Vector6d;
using gasp::expLeft;

Vector6d randomVector(std::mt19937& rng, double sigma_t, double sigma_r) {
  std::normal_distribution<double> n(0.0, 1.0);
  Vector6d v;
  for (int j = 0; j < 3; ++j) v(j) = sigma_t * n(rng), v(j + 3) = sigma_r * n(rng);
  return v;
}

/// A random symmetric positive definite information with correlations, about 1 cm / 0.5 deg.
Matrix6d randomInformation(std::mt19937& rng) {
  Matrix6d B = Matrix6d::Zero();
  std::normal_distribution<double> n(0.0, 1.0);
  for (int r = 0; r < 6; ++r)
    for (int c = 0; c < 6; ++c) B(r, c) = 0.3 * n(rng);
  Vector6d sigma;
  sigma << 0.01, 0.012, 0.008, 0.009, 0.007, 0.011;
  const Matrix6d S = sigma.asDiagonal();
  const Matrix6d cov = S * (Matrix6d::Identity() + B * B.transpose()) * S;
  return cov.inverse();
}

PoseConstraint edge(std::size_t from, std::size_t to, const Isometry3& T, const Matrix6d& info) {
  PoseConstraint c;
  c.from = from, c.to = to, c.T_from_to = T, c.information = info;
  return c;
}

/// Nodes on a bent path far from the world's origin, each turned differently.
std::vector<Isometry3> bentPath(std::size_t n, std::mt19937& rng) {
  std::vector<Isometry3> T(n);
  T[0] = expLeft((Vector6d() << 3.0, -2.0, 1.5, 0.4, -1.1, 2.0).finished());
  for (std::size_t i = 1; i < n; ++i) T[i] = T[i - 1] * expLeft(randomVector(rng, 0.4, 0.5));
  return T;
}

double relativeDifference(const Matrix6d& a, const Matrix6d& b) { return (a - b).norm() / b.norm(); }

/// (J^T J)^-1 over the left world perturbations of the free nodes, J by central differences of the
/// whitened residuals L^T xi_e, xi_e = leftPerturbation(T_from^-1 T_to, T_meas): the cost the
/// optimiser minimises (pose_graph_optimizer.h), written without Ceres.
Eigen::MatrixXd numericalCovariance(const std::vector<Isometry3>& T, const std::vector<PoseConstraint>& edges,
                                    const std::vector<std::size_t>& free_nodes) {
  const auto residuals = [&](const std::vector<Isometry3>& P) {
    Eigen::VectorXd r(6 * edges.size());
    for (std::size_t e = 0; e < edges.size(); ++e) {
      const PoseConstraint& c = edges[e];
      const Eigen::LLT<Matrix6d> llt(c.information);
      const Matrix6d Lt = llt.matrixU();
      r.segment<6>(6 * e) = Lt * gasp::leftPerturbation(P[c.from].inverse() * P[c.to], c.T_from_to);
    }
    return r;
  };
  Eigen::MatrixXd J(6 * edges.size(), 6 * free_nodes.size());
  const double h = 1e-6;
  for (std::size_t k = 0; k < free_nodes.size(); ++k)
    for (int j = 0; j < 6; ++j) {
      Vector6d d = Vector6d::Zero();
      d(j) = h;
      std::vector<Isometry3> plus = T, minus = T;
      plus[free_nodes[k]] = expLeft(d) * T[free_nodes[k]];
      minus[free_nodes[k]] = expLeft(-d) * T[free_nodes[k]];
      J.col(static_cast<Eigen::Index>(6 * k + j)) = (residuals(plus) - residuals(minus)) / (2 * h);
    }
  return (J.transpose() * J).inverse();
}

}  // namespace

TEST(PoseGraphMarginals, AlongAChainTheyAreTheComposedCovariance) {
  std::mt19937 rng(11);
  const std::size_t n = 6;
  const std::vector<Isometry3> T = bentPath(n, rng);
  std::vector<PoseConstraint> edges;
  for (std::size_t i = 1; i < n; ++i) edges.push_back(edge(i - 1, i, T[i - 1].inverse() * T[i], randomInformation(rng)));
  const gasp::PoseGraphMarginals m = gasp::poseGraphMarginals(T, edges);
  ASSERT_TRUE(m.computed) << m.message;
  ASSERT_EQ(m.covariance.size(), n);
  ASSERT_TRUE(m.covariance[0].has_value());
  EXPECT_EQ(m.covariance[0]->norm(), 0.0);  // the root holds the gauge
  for (std::size_t k = 1; k < n; ++k) {
    EXPECT_EQ(m.piece_root[k], 0u);
    const auto composed = gasp::composeAlongTree(edges, n, 0, k);
    ASSERT_TRUE(composed.has_value());
    // composeAlongTree's covariance is in frame 0; the marginal is in the world.
    const Matrix6d Ad = gasp::adjoint(T[0]);
    const Matrix6d expected = Ad * composed->covariance * Ad.transpose();
    ASSERT_TRUE(m.covariance[k].has_value());
    EXPECT_LT(relativeDifference(*m.covariance[k], expected), 1e-6) << "node " << k << "\n" << *m.covariance[k]
                                                                    << "\nexpected\n" << expected;
  }
}

TEST(PoseGraphMarginals, TwoEdgesInParallelAddTheirInformation) {
  std::mt19937 rng(5);
  const std::vector<Isometry3> T = bentPath(2, rng);
  const Matrix6d I1 = randomInformation(rng), I2 = randomInformation(rng);
  const Isometry3 T01 = T[0].inverse() * T[1];
  const gasp::PoseGraphMarginals m = gasp::poseGraphMarginals(T, {edge(0, 1, T01, I1), edge(0, 1, T01, I2)});
  ASSERT_TRUE(m.computed) << m.message;
  const Matrix6d Ad = gasp::adjoint(T[0]);
  const Matrix6d expected = Ad * (I1 + I2).inverse() * Ad.transpose();
  ASSERT_TRUE(m.covariance[1].has_value());
  EXPECT_LT(relativeDifference(*m.covariance[1], expected), 1e-6);
}

TEST(PoseGraphMarginals, WithLoopsTheyAreTheInverseOfTheGaussNewtonMatrix) {
  std::mt19937 rng(8);
  const std::size_t n = 7;
  const std::vector<Isometry3> truth = bentPath(n, rng);
  std::vector<PoseConstraint> edges;
  const auto noisy = [&](std::size_t a, std::size_t b) {
    return edge(a, b, expLeft(randomVector(rng, 0.01, 0.01)) * truth[a].inverse() * truth[b], randomInformation(rng));
  };
  for (std::size_t i = 1; i < n; ++i) edges.push_back(noisy(i - 1, i));
  edges.push_back(noisy(0, 4));
  edges.push_back(noisy(2, 6));
  edges.push_back(noisy(1, 5));
  const gasp::PoseGraphResult opt = gasp::optimizePoseGraph(truth, edges);
  ASSERT_TRUE(opt.converged) << opt.message;
  const gasp::PoseGraphMarginals m = gasp::poseGraphMarginals(opt.T_world_node, edges);
  ASSERT_TRUE(m.computed) << m.message;
  std::vector<std::size_t> free_nodes;
  for (std::size_t i = 1; i < n; ++i) free_nodes.push_back(i);
  const Eigen::MatrixXd reference = numericalCovariance(opt.T_world_node, edges, free_nodes);
  for (std::size_t k = 0; k < free_nodes.size(); ++k) {
    const Matrix6d expected = reference.block<6, 6>(static_cast<Eigen::Index>(6 * k), static_cast<Eigen::Index>(6 * k));
    ASSERT_TRUE(m.covariance[free_nodes[k]].has_value());
    EXPECT_LT(relativeDifference(*m.covariance[free_nodes[k]], expected), 1e-4) << "node " << free_nodes[k];
  }

  // The loop closures make every node surer than the chain alone does.
  const std::vector<PoseConstraint> chain(edges.begin(), edges.begin() + static_cast<long>(n - 1));
  const gasp::PoseGraphMarginals m_chain = gasp::poseGraphMarginals(opt.T_world_node, chain);
  ASSERT_TRUE(m_chain.computed);
  for (std::size_t i = 2; i < n; ++i) {
    const Matrix6d gained = *m_chain.covariance[i] - *m.covariance[i];
    const Eigen::SelfAdjointEigenSolver<Matrix6d> eig(0.5 * (gained + gained.transpose()));
    EXPECT_GT(eig.eigenvalues().minCoeff(), -1e-12) << "node " << i;
    EXPECT_GT(m_chain.covariance[i]->trace(), 1.2 * m.covariance[i]->trace()) << "node " << i;
  }
}

TEST(PoseGraphMarginals, PiecesAreRelativeToTheirRootsAndLoneNodesHaveNone) {
  std::mt19937 rng(2);
  const std::vector<Isometry3> T = bentPath(6, rng);
  const Matrix6d I = randomInformation(rng);
  // Pieces {0, 1}, {3, 4, 5}; node 2 has no edge.
  const std::vector<PoseConstraint> edges = {edge(0, 1, T[0].inverse() * T[1], I), edge(3, 4, T[3].inverse() * T[4], I),
                                             edge(4, 5, T[4].inverse() * T[5], I)};
  const gasp::PoseGraphMarginals m = gasp::poseGraphMarginals(T, edges);
  ASSERT_TRUE(m.computed);
  EXPECT_FALSE(m.covariance[2].has_value());
  for (const std::size_t root : {0u, 3u}) {
    ASSERT_TRUE(m.covariance[root].has_value());
    EXPECT_EQ(m.covariance[root]->norm(), 0.0);
  }
  EXPECT_EQ(m.piece_root[1], 0u);
  EXPECT_EQ(m.piece_root[5], 3u);
  // Node 4 is one edge from its root, as node 1 is from its: the same covariance in the root's frame.
  const Matrix6d in_root_4 = gasp::adjoint(T[3].inverse()) * *m.covariance[4] * gasp::adjoint(T[3].inverse()).transpose();
  const Matrix6d in_root_1 = gasp::adjoint(T[0].inverse()) * *m.covariance[1] * gasp::adjoint(T[0].inverse()).transpose();
  EXPECT_LT(relativeDifference(in_root_4, I.inverse()), 1e-6);
  EXPECT_LT(relativeDifference(in_root_1, I.inverse()), 1e-6);
  EXPECT_GT(m.covariance[5]->trace(), m.covariance[4]->trace());

  // No edges: nothing is known, nothing fails.
  const gasp::PoseGraphMarginals none = gasp::poseGraphMarginals(T, {});
  EXPECT_TRUE(none.computed);
  for (const auto& c : none.covariance) EXPECT_FALSE(c.has_value());
}

TEST(PoseGraphMarginals, ThePositionsCovarianceIsTheSampledOne) {
  // Far from the origin, a rotation's lever arm dominates: the [t] block alone is not the position's.
  std::mt19937 rng(9);
  Isometry3 T = expLeft((Vector6d() << 4.0, -3.0, 2.0, 0.3, 0.2, -0.5).finished());
  const Matrix6d C = randomInformation(rng).inverse();
  const Eigen::Matrix3d expected = gasp::positionCovariance(C, T);
  const Eigen::LLT<Matrix6d> llt(C);
  Eigen::Matrix3d sampled = Eigen::Matrix3d::Zero();
  const int samples = 20000;
  std::normal_distribution<double> n(0.0, 1.0);
  for (int k = 0; k < samples; ++k) {
    Vector6d z;
    for (int j = 0; j < 6; ++j) z(j) = n(rng);
    const Eigen::Vector3d d = (expLeft(llt.matrixL() * z) * T).translation() - T.translation();
    sampled += d * d.transpose() / samples;
  }
  EXPECT_LT((expected - sampled).norm(), 0.05 * sampled.norm()) << expected << "\nsampled\n" << sampled;
  EXPECT_GT((expected - C.topLeftCorner<3, 3>()).norm(), 0.5 * sampled.norm());  // the lever arm matters here
}

TEST(PoseGraphMarginals, AnUnobservableDirectionIsReportedNotInverted) {
  // An edge that pins five directions and leaves the sixth all but free (1e-30 against 1e4):
  // Ceres's sparse QR sees the Jacobian as rank deficient, and no covariance is claimed.
  std::mt19937 rng(1);
  const std::vector<Isometry3> T = bentPath(2, rng);
  Vector6d d;
  d << 1e4, 1e4, 1e4, 1e4, 1e4, 1e-30;
  const gasp::PoseGraphMarginals m = gasp::poseGraphMarginals(T, {edge(0, 1, T[0].inverse() * T[1], d.asDiagonal())});
  EXPECT_FALSE(m.computed);
  EXPECT_NE(m.message.find("rank-deficient"), std::string::npos) << m.message;
  for (const auto& c : m.covariance) EXPECT_FALSE(c.has_value());
}

TEST(PoseGraphMarginals, BadGraphsAreErrors) {
  std::mt19937 rng(4);
  std::vector<Isometry3> T = bentPath(3, rng);
  const Matrix6d I = randomInformation(rng);
  EXPECT_THROW(gasp::poseGraphMarginals(T, {edge(0, 3, Isometry3::Identity(), I)}), gasp::Error);
  EXPECT_THROW(gasp::poseGraphMarginals(T, {edge(1, 1, Isometry3::Identity(), I)}), gasp::Error);
  EXPECT_THROW(gasp::poseGraphMarginals(T, {edge(0, 1, Isometry3::Identity(), Matrix6d::Zero())}), gasp::Error);
  Matrix6d nan_info = I;
  nan_info(2, 2) = std::nan("");
  EXPECT_THROW(gasp::poseGraphMarginals(T, {edge(0, 1, Isometry3::Identity(), nan_info)}), gasp::Error);
  EXPECT_THROW(gasp::poseGraphMarginals(T, {edge(0, 1, Isometry3::Identity(), I)}, 0), gasp::Error);
  T[2].translation().x() = std::nan("");
  EXPECT_THROW(gasp::poseGraphMarginals(T, {edge(0, 1, Isometry3::Identity(), I)}), gasp::Error);
}
