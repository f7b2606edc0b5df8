// Pose-graph algebra (pose_graph.h) and optimisation (pose_graph_optimizer.h) on graphs with a
// known answer.
#include <gtest/gtest.h>

#include <Eigen/Cholesky>

#include <cmath>
#include <random>
#include <vector>

#include "gasp/core/error.h"
#include "gasp/slam/pose_graph.h"
#include "gasp/slam/pose_graph_optimizer.h"

namespace {

using gasp::Isometry3;
using gasp::Matrix6d;
using gasp::PoseConstraint;
using gasp::Vector6d;
using gasp::expLeft;

Matrix6d isotropicInformation(double sigma_t, double sigma_r) {
  Vector6d d;
  d << Eigen::Vector3d::Constant(1 / (sigma_t * sigma_t)), Eigen::Vector3d::Constant(1 / (sigma_r * sigma_r));
  return d.asDiagonal();
}

PoseConstraint edge(std::size_t from, std::size_t to, const Isometry3& T, const Matrix6d& info, bool loop = false) {
  PoseConstraint c;
  c.from = from, c.to = to, c.T_from_to = T, c.information = info, c.loop_closure = loop;
  return c;
}

/// A square loop of n poses around a 2 m circle, turning as it goes.
std::vector<Isometry3> circle(std::size_t n) {
  std::vector<Isometry3> T(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double a = 2 * M_PI * static_cast<double>(i) / static_cast<double>(n);
    T[i] = Isometry3::Identity();
    T[i].linear() = Eigen::AngleAxisd(a, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    T[i].translation() = Eigen::Vector3d(std::cos(a), std::sin(a), 0.1 * std::sin(2 * a));
  }
  return T;
}

}  // namespace

TEST(PoseGraph, LeftPerturbationInvertsExpAndTheAdjointMovesIt) {
  std::mt19937 rng(3);
  std::normal_distribution<double> n(0, 0.3);
  for (int k = 0; k < 50; ++k) {
    Vector6d xi, eta;
    for (int j = 0; j < 6; ++j) xi(j) = n(rng), eta(j) = 1e-4 * n(rng);
    const Isometry3 T = expLeft(xi), P = expLeft(Vector6d::Constant(0.2) + xi);
    EXPECT_LT((gasp::leftPerturbation(expLeft(xi) * T, T) - xi).norm(), 1e-9);
    // P Exp(eta) P^-1 = Exp(Ad(P) eta) to first order.
    const Vector6d moved = gasp::leftPerturbation(P * expLeft(eta) * P.inverse(), Isometry3::Identity());
    EXPECT_LT((moved - gasp::adjoint(P) * eta).norm(), 1e-7 + 1e-3 * eta.norm());
  }
}

TEST(PoseGraph, ComposeAlongTreeGivesTheRelativePoseAndTheSampledCovariance) {
  // A tree 0 -> 1 -> 2 -> 4 and 1 -> 3 -> 5: from 4 to 5 through their common ancestor 1, two
  // constraints on each leg.
  const std::vector<Isometry3> T = circle(8);
  std::vector<PoseConstraint> tree;
  Matrix6d info = isotropicInformation(0.01, 0.01);
  info(0, 4) = info(4, 0) = 2000.0;  // correlated translation and rotation
  for (auto [a, b] : {std::pair<std::size_t, std::size_t>{0, 1}, {1, 2}, {2, 4}, {1, 3}, {3, 5}})
    tree.push_back(edge(a, b, T[a].inverse() * T[b], info));
  const auto est = gasp::composeAlongTree(tree, 6, 4, 5);
  ASSERT_TRUE(est.has_value());
  EXPECT_EQ(est->edges, 4u);
  EXPECT_TRUE(est->T_a_b.isApprox(T[4].inverse() * T[5], 1e-12));
  // Sampled: perturb the four constraints with their covariance, compose, and take the left
  // perturbation in frame 4.
  const Matrix6d L = Eigen::LLT<Matrix6d>(info.inverse()).matrixL();
  std::mt19937 rng(5);
  std::normal_distribution<double> n(0, 1);
  const auto draw = [&](const PoseConstraint& c) {
    Vector6d z;
    for (int j = 0; j < 6; ++j) z(j) = n(rng);
    return Isometry3(expLeft(L * z) * c.T_from_to);
  };
  Matrix6d S = Matrix6d::Zero();
  const int draws = 20000;
  for (int k = 0; k < draws; ++k) {
    const Isometry3 T14 = draw(tree[1]) * draw(tree[2]), T15 = draw(tree[3]) * draw(tree[4]);
    const Vector6d xi = gasp::leftPerturbation(T14.inverse() * T15, est->T_a_b);
    S += xi * xi.transpose() / draws;
  }
  EXPECT_LT((S - est->covariance).norm() / est->covariance.norm(), 0.05);
  // Frames in different pieces: no path.
  EXPECT_FALSE(gasp::composeAlongTree(tree, 7, 2, 6).has_value());
  EXPECT_THROW(gasp::composeAlongTree(tree, 6, 2, 9), gasp::Error);
  tree.push_back(edge(0, 3, Isometry3::Identity(), info));
  EXPECT_THROW(gasp::composeAlongTree(tree, 6, 2, 3), gasp::Error);  // two constraints end in 3
}

TEST(PoseGraph, PieceRootsAreTheLowestIndexOfEachPiece) {
  const Matrix6d info = Matrix6d::Identity();
  const std::vector<PoseConstraint> edges{edge(3, 1, Isometry3::Identity(), info), edge(4, 3, Isometry3::Identity(), info),
                                          edge(5, 6, Isometry3::Identity(), info)};
  const std::vector<std::size_t> roots = gasp::pieceRoots(7, edges);
  EXPECT_EQ(roots, (std::vector<std::size_t>{0, 1, 2, 1, 1, 5, 5}));
  EXPECT_EQ(gasp::pieceCount(7, edges), 4u);
  EXPECT_EQ(gasp::pieceCount(0, {}), 0u);
  EXPECT_THROW(gasp::pieceRoots(3, edges), gasp::Error);
}

TEST(PoseGraphOptimizer, ALoopClosureTakesOutTheDriftOfAChain) {
  // 24 poses on a circle; odometry with random errors drawn from its stated information (1 cm,
  // 0.5 deg per step), and a precise loop closure 0 -> 23. The optimised chain must be closer
  // to the truth than the odometry, most of all at its end, and agree with every constraint.
  const std::size_t n = 24;
  const std::vector<Isometry3> truth = circle(n);
  std::mt19937 rng(11);
  std::normal_distribution<double> noise(0.0, 1.0);
  double odo_sum = 0, opt_sum = 0, odo_end = 0, opt_end = 0;
  const int trials = 20;
  for (int k = 0; k < trials; ++k) {
    std::vector<PoseConstraint> edges;
    std::vector<Isometry3> odo{truth[0]};
    for (std::size_t i = 1; i < n; ++i) {
      Vector6d xi;
      for (int j = 0; j < 3; ++j) xi(j) = 0.01 * noise(rng), xi(j + 3) = 0.5 * M_PI / 180 * noise(rng);
      const Isometry3 meas = expLeft(xi) * (truth[i - 1].inverse() * truth[i]);
      edges.push_back(edge(i - 1, i, meas, isotropicInformation(0.01, 0.5 * M_PI / 180)));
      odo.push_back(odo.back() * meas);
    }
    edges.push_back(edge(0, n - 1, truth[0].inverse() * truth[n - 1], isotropicInformation(0.001, 0.0005), true));
    const gasp::PoseGraphResult r = gasp::optimizePoseGraph(odo, edges);
    ASSERT_TRUE(r.converged) << r.message;
    EXPECT_EQ(r.fixed_nodes, 1u);
    EXPECT_TRUE(r.T_world_node[0].isApprox(truth[0], 1e-12));  // the gauge
    EXPECT_LT(r.final_chi2, r.initial_chi2);
    // At the optimum the chi-square is about that of the noise: 6 per odometry edge at most.
    EXPECT_LT(r.final_chi2, 6.0 * static_cast<double>(n));
    for (std::size_t i = 0; i < n; ++i) {
      odo_sum += (odo[i].translation() - truth[i].translation()).squaredNorm();
      opt_sum += (r.T_world_node[i].translation() - truth[i].translation()).squaredNorm();
    }
    odo_end += (odo[n - 1].translation() - truth[n - 1].translation()).norm();
    opt_end += (r.T_world_node[n - 1].translation() - truth[n - 1].translation()).norm();
  }
  const double odo_rms = std::sqrt(odo_sum / (trials * n)), opt_rms = std::sqrt(opt_sum / (trials * n));
  std::printf("RMS error %.4f m -> %.4f m; last pose %.4f m -> %.4f m (mean of %d chains)\n", odo_rms, opt_rms,
              odo_end / trials, opt_end / trials, trials);
  EXPECT_LT(opt_rms, 0.7 * odo_rms);
  EXPECT_LT(opt_end / trials, 0.005);
  EXPECT_GT(odo_end / trials, 0.03);
}

TEST(PoseGraphOptimizer, ConsistentConstraintsAreAFixedPointAndPiecesKeepTheirPlace) {
  const std::vector<Isometry3> truth = circle(10);
  std::vector<PoseConstraint> edges;
  const Matrix6d info = isotropicInformation(0.01, 0.01);
  for (std::size_t i = 1; i < 5; ++i) edges.push_back(edge(i - 1, i, truth[i - 1].inverse() * truth[i], info));
  for (std::size_t i = 6; i < 10; ++i) edges.push_back(edge(i - 1, i, truth[i - 1].inverse() * truth[i], info));
  edges.push_back(edge(9, 6, truth[9].inverse() * truth[6], info, true));
  // Piece 5..9 starts displaced as a whole: it stays so (nothing ties it to piece 0..4).
  std::vector<Isometry3> start = truth;
  Vector6d shift;
  shift << 1, 2, 3, 0.1, 0.2, 0.3;
  for (std::size_t i = 5; i < 10; ++i) start[i] = expLeft(shift) * truth[i];
  const gasp::PoseGraphResult r = gasp::optimizePoseGraph(start, edges);
  EXPECT_EQ(r.fixed_nodes, 2u);
  EXPECT_LT(r.final_chi2, 1e-12);
  for (std::size_t i = 0; i < 10; ++i) EXPECT_TRUE(r.T_world_node[i].isApprox(start[i], 1e-9)) << i;
}

TEST(PoseGraphOptimizer, NodesThatHangByOneEdgeArePlacedByItAtTheSameOptimum) {
  // A loop of 12 poses with noisy odometry and a loop closure, and hanging off it frames as an
  // odometry's between keyframes: single frames and a branch of three, each edge measured with
  // noise and each frame started elsewhere. Peeled, they are placed by their edges: residual zero.
  // The same graph with every hanging frame also tied to node 0 by a negligible edge (1e-12 of
  // the information) keeps them all in the solve; started from the peeled answer moved by noise
  // (1 cm, 0.5 deg a node), it comes back to it: the leaves' poses and the core's.
  const std::size_t n = 12;
  const std::vector<Isometry3> truth = circle(n);
  std::mt19937 rng(5);
  std::normal_distribution<double> noise(0.0, 1.0);
  const auto noisy = [&](const Isometry3& T) {
    Vector6d xi;
    for (int j = 0; j < 3; ++j) xi(j) = 0.01 * noise(rng), xi(j + 3) = 0.5 * M_PI / 180 * noise(rng);
    return expLeft(xi) * T;
  };
  const Matrix6d info = isotropicInformation(0.01, 0.5 * M_PI / 180);
  std::vector<PoseConstraint> edges;
  std::vector<Isometry3> start{truth[0]};
  for (std::size_t i = 1; i < n; ++i) {
    edges.push_back(edge(i - 1, i, noisy(truth[i - 1].inverse() * truth[i]), info));
    start.push_back(start.back() * edges.back().T_from_to);
  }
  edges.push_back(edge(0, n - 1, truth[0].inverse() * truth[n - 1], isotropicInformation(0.001, 0.0005), true));
  // Hanging frames: 12 off 3, 13 off 7, and the branch 14 <- 15 <- 16 off 10 (16 -> 15 reversed).
  const std::vector<std::pair<std::size_t, std::size_t>> hanging{{3, 12}, {7, 13}, {10, 14}, {14, 15}, {16, 15}};
  start.resize(17, Isometry3::Identity());
  for (const auto& [from, to] : hanging) {
    const Isometry3 T_world_to = noisy(Isometry3(Eigen::Translation3d(0.1 * static_cast<double>(to), 0, 0)) * truth[to % n]);
    if (from == 16) {  // the branch's tip, as the edge's `from`
      start[16] = noisy(truth[5]);
      edges.push_back(edge(16, 15, noisy(start[16].inverse() * T_world_to), info));
      continue;
    }
    if (to != 15) start[to] = T_world_to;
    edges.push_back(edge(from, to, noisy(truth[from % n].inverse() * T_world_to), info));
  }
  const gasp::PoseGraphResult peeled = gasp::optimizePoseGraph(start, edges);
  ASSERT_TRUE(peeled.converged) << peeled.message;
  EXPECT_EQ(peeled.placed_nodes, 5u);
  EXPECT_EQ(peeled.fixed_nodes, 1u);
  for (std::size_t e = n; e < edges.size(); ++e)
    EXPECT_LT(gasp::edgeChi2(peeled.T_world_node[edges[e].from], peeled.T_world_node[edges[e].to], edges[e]), 1e-16) << e;
  std::vector<PoseConstraint> tied = edges;
  for (const std::size_t i : {12, 13, 14, 15, 16})
    tied.push_back(edge(0, i, start[0].inverse() * start[i], 1e-12 * info));
  std::vector<Isometry3> moved = peeled.T_world_node;
  for (std::size_t i = 1; i < moved.size(); ++i) moved[i] = noisy(moved[i]);
  const gasp::PoseGraphResult whole = gasp::optimizePoseGraph(moved, tied);
  ASSERT_TRUE(whole.converged) << whole.message << " (peeled: " << peeled.message << ")";
  EXPECT_EQ(whole.placed_nodes, 0u);
  for (std::size_t i = 0; i < start.size(); ++i) {
    const Isometry3 d = peeled.T_world_node[i].inverse() * whole.T_world_node[i];
    EXPECT_LT(gasp::translationNorm(d), 1e-6) << i;
    EXPECT_LT(gasp::rotationAngle(d), 1e-6) << i;
  }
  // A tree is all placed: nothing to solve, every edge met.
  const std::vector<PoseConstraint> tree(edges.begin(), edges.begin() + static_cast<std::ptrdiff_t>(n - 1));
  const gasp::PoseGraphResult t = gasp::optimizePoseGraph(start, tree);
  EXPECT_TRUE(t.converged);
  EXPECT_EQ(t.placed_nodes, n - 1);
  EXPECT_LT(t.final_chi2, 1e-16);
}

TEST(PoseGraphOptimizer, BadGraphsAreErrorsAndAnEmptyOneIsNothingToDo) {
  const std::vector<Isometry3> nodes(3, Isometry3::Identity());
  EXPECT_THROW(gasp::optimizePoseGraph(nodes, {edge(0, 3, Isometry3::Identity(), Matrix6d::Identity())}), gasp::Error);
  EXPECT_THROW(gasp::optimizePoseGraph(nodes, {edge(1, 1, Isometry3::Identity(), Matrix6d::Identity())}), gasp::Error);
  EXPECT_THROW(gasp::optimizePoseGraph(nodes, {edge(0, 1, Isometry3::Identity(), Matrix6d::Zero())}), gasp::Error);
  Matrix6d nan_info = Matrix6d::Identity();
  nan_info(2, 2) = std::nan("");
  EXPECT_THROW(gasp::optimizePoseGraph(nodes, {edge(0, 1, Isometry3::Identity(), nan_info)}), gasp::Error);
  std::vector<Isometry3> bad = nodes;
  bad[2].translation().x() = INFINITY;
  EXPECT_THROW(gasp::optimizePoseGraph(bad, {}), gasp::Error);
  const gasp::PoseGraphResult r = gasp::optimizePoseGraph(nodes, {});
  EXPECT_TRUE(r.converged);
  EXPECT_EQ(r.T_world_node.size(), 3u);
}
