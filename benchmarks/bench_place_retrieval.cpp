// Place retrieval without appearance (gasp/association/place_descriptor.h): what a query over a
// map of keyframes costs, and, printed first, how often the nearest descriptor is a view of the
// same place on fr3_cabinet_kf (the camera circles the cabinet: opposite sides are other places).
//
//   build/ci/bin/bench_place_retrieval [--keyframes 1000] [benchmark options]
//
// The index holds --keyframes descriptors, cycling through those of fr3_cabinet_kf's 30 frames
// and every 8th frame of fr1_xyz. The report: for each cabinet frame, its nearest descriptor
// among the cabinet frames at least 3 frames away; "same place" when the reference poses are at
// most 0.5 m apart with optical axes at most 45 deg apart (a crude overlap rule, stated here).
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "bench_data.h"
#include "gasp/association/place_descriptor.h"
#include "gasp/association/view_association.h"
#include "gasp/pipeline/depth_view.h"

namespace {

struct Setup {
  std::vector<gasp::PlaceDescriptor> descriptors;  ///< the cabinet's frames first, then fr1_xyz's
  gasp::PlaceIndex index;
};

Setup& setup() {
  static Setup s;
  return s;
}

gasp::PlaceDescriptor describe(const gasp::TumDataset& ds, std::size_t i) {
  const gasp::DepthView v = gasp::makeDepthView(ds.loadDepth(i), ds.intrinsics());
  return gasp::describePlace(gasp::computeFeatureSets(gasp::toPatchGeometry(v.segmentation.patches),
                                                      gasp::AssociationParams{}.feature_sets));
}

void report(const gasp::TumDataset& cabinet) {
  const std::size_t n = cabinet.size();
  int same = 0, compared = 0;
  for (std::size_t i = 0; i < n; ++i) {
    double best = 2.0;
    std::size_t best_j = i;
    for (std::size_t j = 0; j < n; ++j) {
      if ((i > j ? i - j : j - i) < 3) continue;
      const double d = gasp::placeDistance(setup().descriptors[i], setup().descriptors[j]);
      if (d < best) best = d, best_j = j;
    }
    const auto& Ti = cabinet.frame(i).T_world_camera;
    const auto& Tj = cabinet.frame(best_j).T_world_camera;
    if (best_j == i || !Ti || !Tj) continue;
    ++compared;
    const double dist = (Ti->translation() - Tj->translation()).norm();
    const double axes = std::acos(std::clamp(Ti->linear().col(2).dot(Tj->linear().col(2)), -1.0, 1.0)) * 180.0 / M_PI;
    const bool ok = dist <= 0.5 && axes <= 45.0;
    same += ok ? 1 : 0;
    std::printf("cabinet %2zu -> %2zu: distance %.3f, poses %.2f m / %.0f deg apart%s\n", i, best_j, best, dist, axes,
                ok ? "" : "  (another place)");
  }
  std::printf("cabinet: the nearest descriptor is the same place for %d of %d frames\n", same, compared);
}

void load(int keyframes) {
  const auto cabinet = gasp::TumDataset::open(gasp::bench::dataDir() + "/tum/fr3_cabinet_kf");
  const auto xyz = gasp::TumDataset::open(gasp::bench::dataDir() + "/tum/fr1_xyz");
  for (std::size_t i = 0; i < cabinet.size(); ++i) setup().descriptors.push_back(describe(cabinet, i));
  for (std::size_t i = 0; i < xyz.size(); i += 8) setup().descriptors.push_back(describe(xyz, i));
  report(cabinet);
  for (int k = 0; k < keyframes; ++k)
    setup().index.add(static_cast<std::size_t>(k), setup().descriptors[static_cast<std::size_t>(k) % setup().descriptors.size()]);
}

/// One query for the 5 nearest over the whole index.
void BM_PlaceQuery(benchmark::State& state) {
  const auto& s = setup();
  std::size_t k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(s.index.query(s.descriptors[k % s.descriptors.size()], 5));
    ++k;
  }
}
BENCHMARK(BM_PlaceQuery)->Unit(benchmark::kMillisecond);

}  // namespace

int main(int argc, char** argv) {
  std::vector<char*> args;
  const int keyframes = gasp::bench::takeIntOption(argc, argv, "--keyframes", 1000, args);
  if (keyframes < 1 || keyframes > 1000000) {
    std::fprintf(stderr, "error: --keyframes must be 1 to 1000000\n");
    return 2;
  }
  try {
    load(keyframes);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s (set GASP_DATA_DIR to the folder holding tum/fr3_cabinet_kf and tum/fr1_xyz)\n",
                 e.what());
    return 1;
  }
  std::printf("index: %zu descriptors of %zu numbers\n", setup().index.size(),
              setup().descriptors.front().sqrt_frequencies.size());
  int n = static_cast<int>(args.size());
  benchmark::Initialize(&n, args.data());
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
