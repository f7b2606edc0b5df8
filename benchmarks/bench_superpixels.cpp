// Speed of the depth-superpixel decomposition on real 640x480 Kinect frames (fr1_xyz), one core.
//   build/release/bin/bench_superpixels [--frames N] [google benchmark flags]
// Google Benchmark times the whole decomposition (one frame per iteration, cycling through the
// frames); afterwards a table gives the median time of each stage over the frames.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <vector>

#include "bench_data.h"
#include "gasp/core/tum_dataset.h"
#include "gasp/superpixels/depth_superpixels.h"

namespace {

struct Frames {
  std::vector<cv::Mat> depth;
  gasp::CameraIntrinsics intrinsics;
};

Frames& frames() {
  static Frames f;
  return f;
}

void BM_SegmentFr1Xyz(benchmark::State& state) {
  const auto& f = frames();
  std::size_t i = 0, patches = 0;
  for (auto _ : state) {
    const auto seg = gasp::segmentDepthSuperpixels(f.depth[i % f.depth.size()], f.intrinsics);
    patches += seg.patches.size();
    benchmark::DoNotOptimize(seg.labels.data);
    ++i;
  }
  state.counters["patches"] = benchmark::Counter(static_cast<double>(patches), benchmark::Counter::kAvgIterations);
}
BENCHMARK(BM_SegmentFr1Xyz)->Unit(benchmark::kMillisecond)->MinTime(2.0);

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  int n_frames = 40;
  for (int a = 1; a + 1 < argc; ++a)
    if (std::strcmp(argv[a], "--frames") == 0) n_frames = std::atoi(argv[a + 1]);
  const std::string dir = gasp::bench::dataDir() + "/tum/fr1_xyz";
  try {
    const auto ds = gasp::TumDataset::open(dir);
    auto& f = frames();
    f.intrinsics = ds.intrinsics();
    const std::size_t step = std::max<std::size_t>(1, ds.size() / static_cast<std::size_t>(n_frames));
    for (std::size_t i = 0; i < ds.size() && f.depth.size() < static_cast<std::size_t>(n_frames); i += step)
      f.depth.push_back(ds.loadDepth(i));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s (set GASP_DATA_DIR to the folder holding tum/fr1_xyz)\n", e.what());
    return 1;
  }
  std::vector<char*> args;
  for (int a = 0; a < argc; ++a) {
    if (std::strcmp(argv[a], "--frames") == 0) { ++a; continue; }
    args.push_back(argv[a]);
  }
  int n_args = static_cast<int>(args.size());
  benchmark::Initialize(&n_args, args.data());
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();

  // Per-stage medians over the frames (one pass each, after the warm-up above).
  std::vector<double> cloud, normals, components, kmeans, cleanup, patches_ms, total, count;
  for (const auto& d : frames().depth) {
    const auto seg = gasp::segmentDepthSuperpixels(d, frames().intrinsics);
    const auto& t = seg.timings;
    cloud.push_back(t.cloud_ms); normals.push_back(t.normals_ms); components.push_back(t.components_ms);
    kmeans.push_back(t.kmeans_ms); cleanup.push_back(t.cleanup_ms); patches_ms.push_back(t.patches_ms);
    total.push_back(t.total()); count.push_back(static_cast<double>(seg.patches.size()));
  }
  std::printf("\nfr1_xyz, %zu frames, median per stage (ms):\n", frames().depth.size());
  std::printf("| stage | median ms |\n|---|---|\n");
  std::printf("| back-projection | %.1f |\n| depth links + normals | %.1f |\n| smooth components | %.1f |\n"
              "| area k-means | %.1f |\n| clean-up | %.1f |\n| patch records | %.1f |\n| **total** | **%.1f** |\n",
              median(cloud), median(normals), median(components), median(kmeans), median(cleanup),
              median(patches_ms), median(total));
  std::printf("median patches per frame: %.0f\n", median(count));
  return 0;
}
