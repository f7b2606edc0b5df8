// Speed of the whole GASP pair on real 640x480 Kinect frames (fr1_xyz pairs (i, i + 10)): both
// segmentations, association, RANSAC, refinement, guided verification, dense rounds and the
// visibility check.
//   build/release/bin/bench_pair [--pairs N] [--threads T] [google benchmark flags]
// TBB runs with T threads (default 2: the target is "2 threads"). Afterwards a table
// gives the median time of each stage over the pairs.
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <memory>
#include <vector>

#include "bench_data.h"
#include "gasp/core/tum_dataset.h"
#include "gasp/pipeline/pair_registration.h"

namespace {

gasp::bench::DepthPairs& pairs() {
  static gasp::bench::DepthPairs p;
  return p;
}

struct Timing {
  double segmentation = 0, association = 0, ransac = 0, refine = 0, dense = 0, guided = 0, total = 0;
  bool success = false;
};

Timing runPair(std::size_t i) {
  const auto& p = pairs();
  const auto t0 = std::chrono::steady_clock::now();
  const auto& [da, db] = p.depth[i % p.depth.size()];
  const auto [va, vb] = gasp::makeDepthViews(da, db, p.intrinsics);
  const auto t1 = std::chrono::steady_clock::now();
  const auto r = gasp::registerViews(va, vb);
  const auto t2 = std::chrono::steady_clock::now();
  Timing t;
  t.segmentation = std::chrono::duration<double, std::milli>(t1 - t0).count() + r.timings.retry_segmentation_ms;
  t.association = r.timings.association_ms;
  t.ransac = r.timings.ransac_ms;
  t.refine = r.timings.refine_ms;
  t.dense = r.timings.dense_ms + r.timings.certify_ms;  // the column "dense rounds + check"
  t.guided = r.timings.guided_ms;
  t.total = std::chrono::duration<double, std::milli>(t2 - t0).count();
  t.success = r.pose.success;
  return t;
}

void BM_PairFr1Xyz(benchmark::State& state) {
  std::size_t i = 0, ok = 0;
  for (auto _ : state) ok += runPair(i++).success;
  state.counters["estimated"] = benchmark::Counter(static_cast<double>(ok), benchmark::Counter::kAvgIterations);
}
BENCHMARK(BM_PairFr1Xyz)->Unit(benchmark::kMillisecond)->MinTime(5.0);

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  int n_pairs = 10, threads = 2;
  std::vector<char*> args;
  for (int a = 0; a < argc; ++a) {
    if (a + 1 < argc && std::strcmp(argv[a], "--pairs") == 0) { n_pairs = std::atoi(argv[++a]); continue; }
    if (a + 1 < argc && std::strcmp(argv[a], "--threads") == 0) { threads = std::atoi(argv[++a]); continue; }
    args.push_back(argv[a]);
  }
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(std::max(1, threads)));
  try {
    pairs() = gasp::bench::loadFr1XyzPairs(n_pairs);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s (set GASP_DATA_DIR to the folder holding tum/fr1_xyz)\n", e.what());
    return 1;
  }
  int n_args = static_cast<int>(args.size());
  benchmark::Initialize(&n_args, args.data());
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();

  std::vector<double> seg, assoc, ransac, refine, dense, guided, total;
  int ok = 0;
  for (std::size_t i = 0; i < pairs().depth.size(); ++i) {
    const Timing t = runPair(i);
    seg.push_back(t.segmentation); assoc.push_back(t.association); ransac.push_back(t.ransac);
    refine.push_back(t.refine); dense.push_back(t.dense); guided.push_back(t.guided); total.push_back(t.total);
    ok += t.success;
  }
  std::printf("\nmedian ms per stage over %zu fr1_xyz pairs (i, i+10), %d TBB threads (%d estimated):\n",
              pairs().depth.size(), threads, ok);
  std::printf("| both segmentations | association | RANSAC | patch refinement | guided verification | dense rounds + check | whole pair |\n");
  std::printf("|---|---|---|---|---|---|---|\n");
  std::printf("| %.1f | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f |\n", median(seg), median(assoc), median(ransac),
              median(refine), median(guided), median(dense), median(total));
  return 0;
}
