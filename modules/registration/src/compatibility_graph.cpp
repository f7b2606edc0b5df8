#include "compatibility_graph.h"

#include <algorithm>
#include <cmath>

namespace gasp::detail {
namespace {

int popcount(std::uint64_t x) { return __builtin_popcountll(x); }

/// Index of the r-th (0-based) set bit of a bitset of `words` words; the caller ensures it exists.
int selectBit(const std::uint64_t* bits, std::size_t words, int r) {
  for (std::size_t w = 0; w < words; ++w) {
    std::uint64_t x = bits[w];
    const int c = popcount(x);
    if (r >= c) {
      r -= c;
      continue;
    }
    for (; r > 0; --r) x &= x - 1;  // clear the lowest r set bits
    return static_cast<int>(w * 64) + __builtin_ctzll(x);
  }
  return -1;
}

}  // namespace

CompatibilityGraph::CompatibilityGraph(const std::vector<PatchCorrespondence>& c, double edge_tolerance_m,
                                       double normal_tolerance_rad)
    : n_(static_cast<int>(c.size())), words_((c.size() + 63) / 64) {
  bits_.assign(static_cast<std::size_t>(n_) * words_, 0);
  degree_.assign(static_cast<std::size_t>(n_), 0);
  scratch_.assign(words_, 0);
  const double cos_slack = std::cos(normal_tolerance_rad);
  for (int i = 0; i < n_; ++i) {
    const auto& a = c[static_cast<std::size_t>(i)];
    for (int j = i + 1; j < n_; ++j) {
      const auto& b = c[static_cast<std::size_t>(j)];
      const double ds = (a.p_source - b.p_source).norm(), dt = (a.p_target - b.p_target).norm();
      if (std::abs(ds - dt) > edge_tolerance_m || ds == 0.0 || dt == 0.0) continue;
      // |angle_s - angle_t| <= tol  <=>  cos(angle_s - angle_t) >= cos(tol), angles in [0, pi].
      const double cs = std::clamp(a.n_source.dot(b.n_source), -1.0, 1.0);
      const double ct = std::clamp(a.n_target.dot(b.n_target), -1.0, 1.0);
      const double cos_diff = cs * ct + std::sqrt((1.0 - cs * cs) * (1.0 - ct * ct));
      if (cos_diff < cos_slack) continue;
      bits_[static_cast<std::size_t>(i) * words_ + (static_cast<std::size_t>(j) >> 6)] |= std::uint64_t{1} << (j & 63);
      bits_[static_cast<std::size_t>(j) * words_ + (static_cast<std::size_t>(i) >> 6)] |= std::uint64_t{1} << (i & 63);
      ++degree_[static_cast<std::size_t>(i)];
      ++degree_[static_cast<std::size_t>(j)];
    }
  }
  for (int i = 0; i < n_; ++i)
    if (degree_[static_cast<std::size_t>(i)] >= 2) seeds_.push_back(i);
}

bool CompatibilityGraph::drawTriangle(std::mt19937& rng, int& i, int& j, int& k) const {
  if (seeds_.empty()) return false;
  i = seeds_[std::uniform_int_distribution<std::size_t>(0, seeds_.size() - 1)(rng)];
  j = selectBit(row(i), words_, std::uniform_int_distribution<int>(0, degree(i) - 1)(rng));
  const std::uint64_t* ri = row(i);
  const std::uint64_t* rj = row(j);
  int common = 0;
  for (std::size_t w = 0; w < words_; ++w) common += popcount(scratch_[w] = ri[w] & rj[w]);
  if (common == 0) return false;
  k = selectBit(scratch_.data(), words_, std::uniform_int_distribution<int>(0, common - 1)(rng));
  return true;
}

double CompatibilityGraph::probabilityAllIn(const std::vector<int>& members) const {
  if (seeds_.empty()) return 0.0;
  std::vector<std::uint64_t> in(words_, 0);
  for (const int m : members) in[static_cast<std::size_t>(m) >> 6] |= std::uint64_t{1} << (m & 63);
  // P(all in) = sum over i in M, j in N(i) & M of P(i) P(j | i) |N(i)&N(j)&M| / |N(i)&N(j)|,
  // P(i) = 1 / |seeds|, P(j | i) = 1 / deg(i).
  double all_in = 0.0;
  for (const int i : members) {
    if (degree(i) < 2) continue;
    const std::uint64_t* ri = row(i);
    double sum_j = 0.0;
    for (const int j : members) {
      if (!adjacent(i, j)) continue;
      const std::uint64_t* rj = row(j);
      int common = 0, common_in = 0;
      for (std::size_t w = 0; w < words_; ++w) {
        const std::uint64_t x = ri[w] & rj[w];
        common += popcount(x);
        common_in += popcount(x & in[w]);
      }
      if (common > 0) sum_j += static_cast<double>(common_in) / common;
    }
    all_in += sum_j / degree(i);
  }
  all_in /= static_cast<double>(seeds_.size());
  return std::clamp(all_in, 0.0, 1.0);
}

}  // namespace gasp::detail
