// Speed of GASP's association stage (issue 4): associateViews() -- feature sets included -- on
// real fr1_xyz pairs (i, i + 10), 2 TBB threads by default. Google Benchmark times the default
// settings; afterwards a table of the median time against the patch count (the superpixel target
// area is varied to get fewer or more patches per view) and the neighbourhood size k, with the
// share of the exhaustive comparisons the candidate search avoids and the share of the computed
// ones that the bounds / early termination cut.
//   build/ci/bin/bench_association [--pairs N] [--threads T] [--no-table] [google benchmark flags]
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench_data.h"
#include "gasp/association/view_association.h"
#include "gasp/core/tum_dataset.h"
#include "gasp/superpixels/depth_superpixels.h"

namespace {

struct ViewPair {
  std::vector<gasp::PatchGeometry> a, b;
};

gasp::bench::DepthPairs& data() {
  static gasp::bench::DepthPairs d;
  return d;
}

std::vector<ViewPair> segmentAll(double target_area_m2) {
  gasp::SuperpixelParams sp;
  sp.target_patch_area_m2 = target_area_m2;
  std::vector<ViewPair> out;
  for (const auto& [da, db] : data().depth)
    out.push_back({gasp::toPatchGeometry(gasp::segmentDepthSuperpixels(da, data().intrinsics, sp).patches),
                   gasp::toPatchGeometry(gasp::segmentDepthSuperpixels(db, data().intrinsics, sp).patches)});
  return out;
}

const std::vector<ViewPair>& defaultViews() {
  static const std::vector<ViewPair> v = segmentAll(gasp::SuperpixelParams{}.target_patch_area_m2);
  return v;
}

void BM_AssociateFr1Xyz(benchmark::State& state) {
  const auto& views = defaultViews();
  std::size_t i = 0, n = 0;
  for (auto _ : state) {
    const auto& v = views[i++ % views.size()];
    n += gasp::associateViews(v.a, v.b).associations.size();
  }
  state.counters["associations"] = benchmark::Counter(static_cast<double>(n), benchmark::Counter::kAvgIterations);
}
BENCHMARK(BM_AssociateFr1Xyz)->Unit(benchmark::kMillisecond)->MinTime(3.0);

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

void printTable(int threads) {
  std::printf("\nassociateViews() on %zu fr1_xyz pairs (i, i+10), %d TBB threads; medians over the pairs\n",
              data().depth.size(), threads);
  std::printf("| target patch area [cm^2] | patches per view | k | features ms | matching ms (incl. preparation) | total ms | comparisons avoided by the candidate search | computed comparisons cut by bounds / early termination |\n");
  std::printf("|---|---|---|---|---|---|---|---|\n");
  for (const double area_cm2 : {80.0, 40.0, 20.0, 10.0}) {
    const auto views = segmentAll(area_cm2 * 1e-4);
    for (const int k : {10, 20, 30, 50}) {
      gasp::AssociationParams p;
      p.feature_sets.neighbourhood.k = k;
      std::vector<double> patches, feat, match, total, avoided, cut;
      for (const auto& v : views) {
        const auto t0 = std::chrono::steady_clock::now();
        const auto r = gasp::associateViews(v.a, v.b, p);
        total.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
        feat.push_back(r.stats.features_ms);
        match.push_back(r.stats.tree_ms + r.stats.matching_ms);
        patches.push_back(0.5 * static_cast<double>(v.a.size() + v.b.size()));
        const auto& s = r.stats;
        avoided.push_back(s.comparisons_full ? 1.0 - static_cast<double>(s.comparisons) / static_cast<double>(s.comparisons_full) : 0.0);
        cut.push_back(s.comparisons ? static_cast<double>(s.cut_early) / static_cast<double>(s.comparisons) : 0.0);
      }
      std::printf("| %.0f | %.0f | %d | %.1f | %.1f | %.1f | %.3f | %.3f |\n", area_cm2, median(patches), k, median(feat),
                  median(match), median(total), median(avoided), median(cut));
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  int n_pairs = 8, threads = 2;
  bool table = true;
  std::vector<char*> args;
  for (int a = 0; a < argc; ++a) {
    if (a + 1 < argc && std::strcmp(argv[a], "--pairs") == 0) { n_pairs = std::atoi(argv[++a]); continue; }
    if (a + 1 < argc && std::strcmp(argv[a], "--threads") == 0) { threads = std::atoi(argv[++a]); continue; }
    if (std::strcmp(argv[a], "--no-table") == 0) { table = false; continue; }
    args.push_back(argv[a]);
  }
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(std::max(1, threads)));
  try {
    data() = gasp::bench::loadFr1XyzPairs(n_pairs);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s (set GASP_DATA_DIR to the folder holding tum/fr1_xyz)\n", e.what());
    return 1;
  }
  int n_args = static_cast<int>(args.size());
  benchmark::Initialize(&n_args, args.data());
  benchmark::RunSpecifiedBenchmarks();
  if (table) printTable(threads);
  return 0;
}
