// What a particle filter pays for gasp::CSuperpixelMap's observation likelihood: the first pose
// of an observation (segmentation and association against the map, then the score) and every
// further pose of the same observation (the score only; the rest is reused).
//
//   build/ci/bin/bench_likelihood [--views 1] [benchmark options]
//
// The map holds --views frames of tum/fr1_xyz (0, 10, ...) at their ground-truth poses; the
// observations are frames 5 and 15, scored at poses jittered around their ground truth.
#include <benchmark/benchmark.h>
#include <mrpt/obs/CObservation3DRangeScan.h>

#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

#include "bench_data.h"
#include "gasp/mrpt/CSuperpixelMap.h"
#include "gasp/rawlog/observation_conversion.h"
#include "gasp/rawlog/tum_to_rawlog.h"

namespace {

struct Setup {
  gasp::CSuperpixelMap map;
  std::vector<mrpt::obs::CObservation3DRangeScan::Ptr> observations;
  std::vector<std::vector<mrpt::poses::CPose3D>> poses;  ///< per observation, 100 jittered poses
};

Setup& setup() {
  static Setup s;
  return s;
}

void load(int views) {
  const auto ds = gasp::TumDataset::open(gasp::bench::dataDir() + "/tum/fr1_xyz");
  for (int v = 0; v < views; ++v) {
    const gasp::RgbdFrame f = gasp::frameFromTum(ds, static_cast<std::size_t>(10 * v), false);
    setup().map.insertFrame(f, *ds.frame(static_cast<std::size_t>(10 * v)).T_world_camera *
                                   f.T_robot_camera.inverse());
  }
  std::mt19937 rng(1);
  std::normal_distribution<double> noise(0.0, 0.05);
  for (std::size_t i : {5u, 15u}) {
    const gasp::RgbdFrame f = gasp::frameFromTum(ds, i, false);
    setup().observations.push_back(gasp::observationFromFrame(f));
    const gasp::Isometry3 T_world_robot = *ds.frame(i).T_world_camera * f.T_robot_camera.inverse();
    std::vector<mrpt::poses::CPose3D> poses;
    for (int k = 0; k < 100; ++k) {
      gasp::Isometry3 jitter = gasp::Isometry3::Identity();
      jitter.translation() = Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
      jitter.linear() = Eigen::AngleAxisd(noise(rng), Eigen::Vector3d::UnitZ()).toRotationMatrix();
      poses.push_back(gasp::toCPose3D(jitter * T_world_robot));
    }
    setup().poses.push_back(poses);
  }
}

/// Every call a new observation (the two alternate): segmentation, association and score.
void BM_LikelihoodNewObservation(benchmark::State& state) {
  auto& s = setup();
  std::size_t k = 0;
  for (auto _ : state) {
    const std::size_t o = k % 2;
    benchmark::DoNotOptimize(s.map.computeObservationLikelihood(*s.observations[o], s.poses[o][k % 100]));
    ++k;
  }
}
BENCHMARK(BM_LikelihoodNewObservation)->Unit(benchmark::kMillisecond)->MinTime(2.0);

/// The same observation at further poses (the particles after the first): the score only.
void BM_LikelihoodFurtherPose(benchmark::State& state) {
  auto& s = setup();
  s.map.computeObservationLikelihood(*s.observations[0], s.poses[0][0]);
  std::size_t k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(s.map.computeObservationLikelihood(*s.observations[0], s.poses[0][k % 100]));
    ++k;
  }
}
BENCHMARK(BM_LikelihoodFurtherPose)->Unit(benchmark::kMillisecond)->MinTime(2.0);

}  // namespace

int main(int argc, char** argv) {
  std::vector<char*> args;
  const int views = gasp::bench::takeIntOption(argc, argv, "--views", 1, args);
  if (views < 1 || views > 70) {
    std::fprintf(stderr, "error: --views must be 1 to 70\n");
    return 2;
  }
  try {
    load(views);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s (set GASP_DATA_DIR to the folder holding tum/fr1_xyz)\n", e.what());
    return 1;
  }
  std::printf("map: %d views, %zu patches\n", views, setup().map.patchCount());
  int n = static_cast<int>(args.size());
  benchmark::Initialize(&n, args.data());
  benchmark::RunSpecifiedBenchmarks();
  const auto stats = setup().map.likelihoodCacheStats();
  std::printf("likelihood cache: %zu hits, %zu misses\n", stats.hits, stats.misses);
  benchmark::Shutdown();
  return 0;
}
