#include "contiguity.h"

#include <algorithm>
#include <vector>

#include "disjoint_sets.h"

namespace gasp::detail {

// Union-find over horizontal runs (maximal linked pixels of one label in a row) instead of
// pixels: a run is some 10-30 pixels, so there are that many times fewer finds and unions. Runs
// of consecutive rows are matched by a merge sweep over their column ranges.
int keepLargestPieces(cv::Mat& labels, const DepthLinks& links, int* pixel_counts, std::vector<int>* removed_pixels) {
  const int w = labels.cols, h = labels.rows;
  int* L = labels.ptr<int>(0);
  struct Run {
    int row, begin, end, label;  // columns [begin, end)
  };
  std::vector<Run> runs;
  runs.reserve(static_cast<std::size_t>(h) * 16);
  DisjointSets sets(0);
  int max_label = -1;
  std::size_t prev_first = 0;
  for (int v = 0; v < h; ++v) {
    const int row = v * w;
    const std::size_t first = runs.size();
    for (int u = 0; u < w;) {
      const int l = L[row + u];
      if (l < 0) {
        ++u;
        continue;
      }
      max_label = std::max(max_label, l);
      const int begin = u;
      while (u + 1 < w && L[row + u + 1] == l && (links.bits(row + u) & DepthLinks::kRight)) ++u;
      runs.push_back({v, begin, ++u, l});
      sets.add();
    }
    // Runs of the row above and of this row that overlap, carry one label and are linked
    // somewhere in the overlap belong to one piece.
    std::size_t a = prev_first, b = first;
    while (v > 0 && a < first && b < runs.size()) {
      const Run &ra = runs[a], &rb = runs[b];
      const int lo = std::max(ra.begin, rb.begin), hi = std::min(ra.end, rb.end);
      if (lo < hi && ra.label == rb.label) {
        for (int u = lo; u < hi; ++u)
          if (links.bits(row - w + u) & DepthLinks::kDown) {
            sets.unite(static_cast<int>(a), static_cast<int>(b));
            break;
          }
      }
      if (ra.end < rb.end) ++a;
      else ++b;
    }
    prev_first = first;
  }
  const int n_runs = static_cast<int>(runs.size());
  std::vector<int> piece_size(static_cast<std::size_t>(n_runs), 0);
  for (int r = 0; r < n_runs; ++r) piece_size[static_cast<std::size_t>(sets.find(r))] += runs[r].end - runs[r].begin;
  std::vector<int> best_root(static_cast<std::size_t>(max_label + 1), -1);  // largest piece per label
  for (int r = 0; r < n_runs; ++r) {
    const int root = sets.find(r);
    int& best = best_root[static_cast<std::size_t>(runs[r].label)];
    if (best < 0 || piece_size[root] > piece_size[best] || (piece_size[root] == piece_size[best] && root < best))
      best = root;
  }
  int removed = 0;
  for (int r = 0; r < n_runs; ++r) {
    const Run& run = runs[static_cast<std::size_t>(r)];
    if (sets.find(r) == best_root[static_cast<std::size_t>(run.label)]) continue;
    std::fill(L + run.row * w + run.begin, L + run.row * w + run.end, -1);
    removed += run.end - run.begin;
    if (pixel_counts) pixel_counts[run.label] -= run.end - run.begin;
    if (removed_pixels)
      for (int u = run.begin; u < run.end; ++u) removed_pixels->push_back(run.row * w + u);
  }
  return removed;
}

}  // namespace gasp::detail
