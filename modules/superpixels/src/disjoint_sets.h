#pragma once
// Union-find with path halving and union by index (the smaller root wins, so results do not
// depend on the order of unions: deterministic labelling).
#include <numeric>
#include <vector>

namespace gasp::detail {

class DisjointSets {
 public:
  explicit DisjointSets(std::size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0); }
  /// Adds a singleton set; returns its id.
  int add() {
    parent_.push_back(static_cast<int>(parent_.size()));
    return parent_.back();
  }
  int find(int x) {
    while (parent_[static_cast<std::size_t>(x)] != x) {
      auto& px = parent_[static_cast<std::size_t>(x)];
      px = parent_[static_cast<std::size_t>(px)];
      x = px;
    }
    return x;
  }
  void unite(int a, int b) {
    a = find(a);
    b = find(b);
    if (a == b) return;
    if (a < b) parent_[static_cast<std::size_t>(b)] = a;
    else parent_[static_cast<std::size_t>(a)] = b;
  }

 private:
  std::vector<int> parent_;
};

}  // namespace gasp::detail
