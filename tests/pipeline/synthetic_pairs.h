#pragma once
// Simulator view pairs for the pipeline tests: one simulation per (scene, noise seed), built
// once per test binary, and pairs of its frames segmented with the default parameters.
#include <cmath>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <utility>

#include "gasp/core/pose.h"
#include "gasp/pipeline/depth_view.h"
#include "gasp/pipeline/pair_registration.h"
#include "gasp/sim/simulation.h"

namespace gasp::test {

inline const sim::Simulation& simulation(const std::string& scene, std::uint64_t seed = 1) {
  static std::map<std::pair<std::string, std::uint64_t>, std::unique_ptr<sim::Simulation>> cache;
  auto& s = cache[{scene, seed}];
  if (!s) {
    sim::SimulationOptions o;
    o.scene = scene;
    o.seed = seed;
    s = std::make_unique<sim::Simulation>(o);
  }
  return *s;
}

struct Pair {
  DepthView a, b;
  Isometry3 T_b_a;  ///< ground truth: frame i's camera in frame j's
};

inline Pair makePair(const std::string& scene, int i, int j, std::uint64_t seed = 1) {
  const auto& s = simulation(scene, seed);
  const auto fa = s.frame(i), fb = s.frame(j);
  const auto K = sim::SimulationOptions{}.intrinsics;
  return {makeDepthView(fa.depth, K), makeDepthView(fb.depth, K), relativePose(fb.T_world_camera, fa.T_world_camera)};
}

/// The estimate's error against the pair's ground truth: translation [m], rotation [deg].
inline double translationError(const Pair& p, const PairResult& r) {
  return translationNorm(p.T_b_a.inverse() * r.pose.T_target_source);
}
inline double rotationErrorDeg(const Pair& p, const PairResult& r) {
  return rotationAngle(p.T_b_a.inverse() * r.pose.T_target_source) * 180.0 / M_PI;
}

}  // namespace gasp::test
