// Speed of the depth-superpixel decomposition on real 640x480 Kinect frames (fr1_xyz).
//   build/release/bin/bench_superpixels [--frames N] [--no-crease-borders] [--step-borders] [google benchmark flags]
// Google Benchmark times the whole decomposition on one thread (one frame per iteration, cycling
// through the frames) and a pair of frames segmented at once on two threads, one frame each (the
// pair pipeline's case; wall time), the lens undistortion of one fr1 depth frame (done when a
// frame is loaded, before segmentation) and its rolling-shutter deskew. Afterwards a table gives
// the median time of each stage over the frames, one thread, and the median wall time of a pair
// on two threads.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <future>
#include <vector>

#include "bench_data.h"
#include "gasp/core/rolling_shutter.h"
#include "gasp/core/tum_dataset.h"
#include "gasp/superpixels/depth_superpixels.h"

namespace {

struct Frames {
  std::vector<cv::Mat> depth;
  gasp::CameraIntrinsics intrinsics;
  gasp::CameraIntrinsics calibrated;  ///< with fr1's distortion coefficients
};

Frames& frames() {
  static Frames f;
  return f;
}

/// Defaults, or crease_borders off with --no-crease-borders, step_borders on with --step-borders
/// (the cost of those stages, A/B).
gasp::SuperpixelParams& params() {
  static gasp::SuperpixelParams p;
  return p;
}

void BM_SegmentFr1Xyz(benchmark::State& state) {
  const auto& f = frames();
  std::size_t i = 0, patches = 0;
  for (auto _ : state) {
    const auto seg = gasp::segmentDepthSuperpixels(f.depth[i % f.depth.size()], f.intrinsics, params());
    patches += seg.patches.size();
    benchmark::DoNotOptimize(seg.labels.data);
    ++i;
  }
  state.counters["patches"] = benchmark::Counter(static_cast<double>(patches), benchmark::Counter::kAvgIterations);
}
BENCHMARK(BM_SegmentFr1Xyz)->Unit(benchmark::kMillisecond)->MinTime(2.0);

/// Frames i and i + 1 segmented at once, each on its own thread.
std::size_t segmentPair(std::size_t i) {
  const auto& f = frames();
  auto other = std::async(std::launch::async, [&] {
    return gasp::segmentDepthSuperpixels(f.depth[(i + 1) % f.depth.size()], f.intrinsics, params()).patches.size();
  });
  const std::size_t n = gasp::segmentDepthSuperpixels(f.depth[i % f.depth.size()], f.intrinsics, params()).patches.size();
  return n + other.get();
}

void BM_SegmentPairTwoThreads(benchmark::State& state) {
  std::size_t i = 0, patches = 0;
  for (auto _ : state) {
    patches += segmentPair(i);
    i += 2;
  }
  state.counters["patches"] = benchmark::Counter(static_cast<double>(patches), benchmark::Counter::kAvgIterations);
}
BENCHMARK(BM_SegmentPairTwoThreads)->Unit(benchmark::kMillisecond)->MinTime(2.0)->UseRealTime();

void BM_UndistortFr1Depth(benchmark::State& state) {
  const gasp::Undistortion undistortion(frames().calibrated);  // maps built once, as in TumDataset
  const cv::Mat& depth = frames().depth.front();
  for (auto _ : state) {
    const cv::Mat out = undistortion.applyToDepth(depth);
    benchmark::DoNotOptimize(out.data);
  }
}
BENCHMARK(BM_UndistortFr1Depth)->Unit(benchmark::kMillisecond)->MinTime(1.0);

/// The rolling-shutter deskew of one (undistorted) fr1 depth frame at a typical fr1_xyz velocity
/// (0.35 m/s, 15 deg/s) and TUM's Kinect readout (30 ms); the neighbours' registration that
/// measures the velocity is not included (bench_pair times a pair).
void BM_DeskewFr1Depth(benchmark::State& state) {
  gasp::CameraTwist twist;
  twist.v_mps = Eigen::Vector3d(0.25, -0.15, 0.2);
  twist.w_radps = Eigen::Vector3d(0.15, 0.2, -0.05);
  const cv::Mat& depth = frames().depth.front();
  for (auto _ : state) {
    const cv::Mat out = gasp::deskewDepth(depth, frames().intrinsics, twist, 0.03);
    benchmark::DoNotOptimize(out.data);
  }
}
BENCHMARK(BM_DeskewFr1Depth)->Unit(benchmark::kMillisecond)->MinTime(1.0);

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  int n_frames = 40;
  for (int a = 1; a < argc; ++a) {
    if (a + 1 < argc && std::strcmp(argv[a], "--frames") == 0) n_frames = std::atoi(argv[a + 1]);
    if (std::strcmp(argv[a], "--no-crease-borders") == 0) params().borders.crease_borders = false;
    if (std::strcmp(argv[a], "--step-borders") == 0) params().borders.step_borders = true;
  }
  const std::string dir = gasp::bench::dataDir() + "/tum/fr1_xyz";
  try {
    const auto ds = gasp::TumDataset::open(dir);
    auto& f = frames();
    f.intrinsics = ds.intrinsics();
    f.calibrated = ds.calibratedIntrinsics();
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
    if (std::strcmp(argv[a], "--no-crease-borders") == 0 || std::strcmp(argv[a], "--step-borders") == 0) continue;
    args.push_back(argv[a]);
  }
  int n_args = static_cast<int>(args.size());
  benchmark::Initialize(&n_args, args.data());
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();

  // Per-stage medians over the frames (one pass each, after the warm-up above).
  std::vector<double> cloud, normals, components, kmeans, cleanup, refine, patches_ms, total, count;
  for (const auto& d : frames().depth) {
    const auto seg = gasp::segmentDepthSuperpixels(d, frames().intrinsics, params());
    const auto& t = seg.timings;
    cloud.push_back(t.cloud_ms); normals.push_back(t.normals_ms); components.push_back(t.components_ms);
    kmeans.push_back(t.kmeans_ms); cleanup.push_back(t.cleanup_ms); refine.push_back(t.refine_ms);
    patches_ms.push_back(t.patches_ms);
    total.push_back(t.total()); count.push_back(static_cast<double>(seg.patches.size()));
  }
  std::printf("\nfr1_xyz, %zu frames, median per stage (ms):\n", frames().depth.size());
  std::printf("| stage | median ms |\n|---|---|\n");
  std::printf("| back-projection, depth links, 2x2 grid | %.1f |\n| normals (grid) | %.1f |\n"
              "| smooth components (grid) | %.1f |\n| area k-means (grid) | %.1f |\n| clean-up (grid) | %.1f |\n"
              "| full-resolution labels | %.1f |\n| patch records | %.1f |\n| **total** | **%.1f** |\n",
              median(cloud), median(normals), median(components), median(kmeans), median(cleanup), median(refine),
              median(patches_ms), median(total));
  std::printf("median patches per frame: %.0f\n", median(count));

  std::vector<double> pair;
  for (std::size_t i = 0; i < frames().depth.size(); i += 2) {
    const auto t0 = std::chrono::steady_clock::now();
    segmentPair(i);
    pair.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  }
  std::printf("pair of frames on 2 threads (one frame each), median wall time: %.1f ms\n", median(pair));
  return 0;
}
