#include "gasp/slam/pose_graph.h"

#include <Eigen/Cholesky>

#include <algorithm>
#include <string>

#include "gasp/core/error.h"

namespace gasp {

Matrix6d covarianceOf(const PoseConstraint& c) {
  const Eigen::LDLT<Matrix6d> ldlt(c.information);
  if (ldlt.info() != Eigen::Success || !ldlt.isPositive() || !(ldlt.vectorD().array() > 0.0).all() ||
      !c.information.allFinite())
    throw Error("pose graph: the information of constraint " + std::to_string(c.from) + " -> " +
                std::to_string(c.to) + " is not positive definite");
  return ldlt.solve(Matrix6d::Identity());
}

double edgeChi2(const Isometry3& T_world_from, const Isometry3& T_world_to, const PoseConstraint& c) {
  const Vector6d xi = leftPerturbation(T_world_from.inverse() * T_world_to, c.T_from_to);
  return xi.dot(c.information * xi);
}

std::optional<Contradiction> mostContradictedClosure(const std::vector<Isometry3>& T_world_node,
                                                     const std::vector<PoseConstraint>& edges, double gate_chi2) {
  std::optional<Contradiction> worst;
  double worst_chi2 = gate_chi2;
  for (std::size_t j = 0; j < edges.size(); ++j) {
    const PoseConstraint& c = edges[j];
    if (!c.loop_closure) continue;
    if (c.from >= T_world_node.size() || c.to >= T_world_node.size())
      throw Error("pose graph: an edge names node " + std::to_string(std::max(c.from, c.to)) + " of " +
                  std::to_string(T_world_node.size()));
    const double chi2 = edgeChi2(T_world_node[c.from], T_world_node[c.to], c);
    if (chi2 > worst_chi2) worst = Contradiction{j, chi2}, worst_chi2 = chi2;
  }
  return worst;
}

std::optional<RelativePoseEstimate> composeAlongTree(const std::vector<PoseConstraint>& tree, std::size_t frame_count,
                                                     std::size_t a, std::size_t b) {
  if (a >= frame_count || b >= frame_count)
    throw Error("pose graph: frame " + std::to_string(a >= frame_count ? a : b) + " is out of range (" +
                std::to_string(frame_count) + " frames)");
  constexpr std::size_t kNone = static_cast<std::size_t>(-1);
  std::vector<std::size_t> parent_edge(frame_count, kNone);
  for (std::size_t e = 0; e < tree.size(); ++e) {
    const PoseConstraint& c = tree[e];
    if (c.from >= frame_count || c.to >= frame_count || c.from == c.to)
      throw Error("pose graph: constraint " + std::to_string(c.from) + " -> " + std::to_string(c.to) +
                  " names a frame out of range or links a frame to itself");
    if (parent_edge[c.to] != kNone)
      throw Error("pose graph: two constraints end in frame " + std::to_string(c.to) + ": not a tree");
    parent_edge[c.to] = e;
  }
  // Ancestors of a (a itself first), then walk up from b to the first of them.
  std::vector<std::size_t> depth_of(frame_count, kNone);
  std::vector<std::size_t> chain_a{a};
  depth_of[a] = 0;
  for (std::size_t x = a; parent_edge[x] != kNone;) {
    x = tree[parent_edge[x]].from;
    if (depth_of[x] != kNone) throw Error("pose graph: the constraints form a cycle: not a tree");
    depth_of[x] = chain_a.size();
    chain_a.push_back(x);
  }
  std::vector<std::size_t> chain_b{b};
  while (depth_of[chain_b.back()] == kNone) {
    const std::size_t x = chain_b.back();
    if (parent_edge[x] == kNone) return std::nullopt;
    if (chain_b.size() > frame_count) throw Error("pose graph: the constraints form a cycle: not a tree");
    chain_b.push_back(tree[parent_edge[x]].from);
  }
  const std::size_t lca = chain_b.back();
  chain_a.resize(depth_of[lca] + 1);

  // Pose and covariance (left perturbation in the ancestor's frame) of a frame below the ancestor.
  RelativePoseEstimate out;
  const auto down = [&](const std::vector<std::size_t>& chain, Isometry3& T, Matrix6d& S) {
    T = Isometry3::Identity();
    S = Matrix6d::Zero();
    for (std::size_t k = chain.size() - 1; k-- > 0;) {  // from the ancestor's child down to chain[0]
      const PoseConstraint& c = tree[parent_edge[chain[k]]];
      const Matrix6d Ad = adjoint(T);
      S += Ad * covarianceOf(c) * Ad.transpose();
      T = T * c.T_from_to;
      ++out.edges;
    }
  };
  Isometry3 T_lca_a, T_lca_b;
  Matrix6d S_a, S_b;
  down(chain_a, T_lca_a, S_a);
  down(chain_b, T_lca_b, S_b);
  const Isometry3 T_a_lca = T_lca_a.inverse();
  out.T_a_b = T_a_lca * T_lca_b;
  const Matrix6d Ad = adjoint(T_a_lca);
  out.covariance = Ad * (S_a + S_b) * Ad.transpose();
  return out;
}

std::vector<std::size_t> pieceRoots(std::size_t node_count, const std::vector<PoseConstraint>& edges) {
  std::vector<std::size_t> parent(node_count);
  for (std::size_t i = 0; i < node_count; ++i) parent[i] = i;
  const auto root = [&parent](std::size_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  for (const PoseConstraint& c : edges) {
    if (c.from >= node_count || c.to >= node_count)
      throw Error("pose graph: constraint " + std::to_string(c.from) + " -> " + std::to_string(c.to) +
                  " names a node out of range (" + std::to_string(node_count) + " nodes)");
    const std::size_t x = root(c.from), y = root(c.to);
    if (x < y) parent[y] = x;
    else if (y < x) parent[x] = y;
  }
  for (std::size_t i = 0; i < node_count; ++i) parent[i] = root(i);
  return parent;
}

std::size_t pieceCount(std::size_t node_count, const std::vector<PoseConstraint>& edges) {
  const std::vector<std::size_t> roots = pieceRoots(node_count, edges);
  std::size_t n = 0;
  for (std::size_t i = 0; i < node_count; ++i) n += roots[i] == i ? 1 : 0;
  return n;
}

}  // namespace gasp
