#pragma once
// Internal: which pairs of patch correspondences can both be right (rigid motions keep the
// distance between two centroids and the angle between two normals), as adjacency bitsets, and
// sampling of minimal 3-sets from its triangles (used by ransacPose()).
#include <cstdint>
#include <random>
#include <vector>

#include "gasp/registration/correspondence.h"

namespace gasp::detail {

class CompatibilityGraph {
 public:
  /// Nodes i and j are adjacent when |d_s(i,j) - d_t(i,j)| <= edge_tolerance_m, the angles
  /// between their normals agree within normal_tolerance_rad in both views, and they share
  /// neither their source nor their target centroid (one patch cannot have two partners).
  CompatibilityGraph(const std::vector<PatchCorrespondence>& c, double edge_tolerance_m, double normal_tolerance_rad);

  int size() const { return n_; }
  int degree(int i) const { return degree_[static_cast<std::size_t>(i)]; }
  bool adjacent(int i, int j) const { return (row(i)[j >> 6] >> (j & 63)) & 1u; }
  /// Nodes of degree >= 2: the only ones that can start a triangle.
  const std::vector<int>& seeds() const { return seeds_; }

  /// A triangle (i, j, k): i uniform over seeds(), j uniform over N(i), k uniform over
  /// N(i) & N(j). False when N(i) & N(j) is empty (the draw counts as a rejected sample).
  /// Precondition: seeds() is not empty. Not thread-safe (uses a scratch bitset).
  bool drawTriangle(std::mt19937& rng, int& i, int& j, int& k) const;

  /// Probability that one drawTriangle() call returns three members of `members` (node
  /// indices): the adaptive RANSAC stopping rule for this sampler (the e^3 of uniform sampling).
  double probabilityAllIn(const std::vector<int>& members) const;

 private:
  const std::uint64_t* row(int i) const { return bits_.data() + static_cast<std::size_t>(i) * words_; }
  int n_ = 0;
  std::size_t words_ = 0;
  std::vector<std::uint64_t> bits_;  // n_ rows of words_ words
  std::vector<int> degree_;
  std::vector<int> seeds_;
  mutable std::vector<std::uint64_t> scratch_;
};

}  // namespace gasp::detail
