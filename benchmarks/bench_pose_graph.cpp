// The pose graph's optimisation (gasp/slam/pose_graph_optimizer.h) at the sizes of a large
// map-building job: what one optimisation costs as the graph grows, for docs/benchmarks.md's
// model of 100 sessions x 500 keyframes.
//
//   build/ci/bin/bench_pose_graph [benchmark options]
//
// The graph is an odometry's with loop closures: K keyframes along a winding path, each tracked
// against the one before (1 cm, 0.5 deg of noise per step) with 11 frames hanging off it as a
// sequence's frames between keyframes do (tracked against their keyframe), and a loop closure
// (1 mm, 0.03 deg) from every 10th keyframe to the one 50 before: 12 K nodes.
//
// What is timed is what DepthSlam pays after each keyframe that takes a closure: the graph
// optimised before the last closure, the last closure added, optimised again from there.
// BM_OptimisePoseGraph is the optimiser as it is (the hanging frames placed by their edges).
// BM_OptimiseEveryNode is the same graph with no node left hanging: each hanging frame is also
// tied to its keyframe's predecessor by an edge of 1e-12 of the information, which moves nothing,
// so every node is an unknown -- with about twice the residual blocks, so it is not the optimiser
// before it placed hanging nodes, only a bound on what keeping them costs. Counters: nodes, those
// optimised, Ceres iterations.
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#include "gasp/slam/pose_graph.h"
#include "gasp/slam/pose_graph_optimizer.h"

namespace {

using gasp::Isometry3;
using gasp::Matrix6d;
using gasp::PoseConstraint;
using gasp::Vector6d;

struct Graph {
  std::vector<Isometry3> T_world_node;  ///< the keyframes at the truth, each frame where its edge puts it
  std::vector<PoseConstraint> edges;
};

Matrix6d information(double sigma_t, double sigma_r) {
  Vector6d d;
  d << Eigen::Vector3d::Constant(1 / (sigma_t * sigma_t)), Eigen::Vector3d::Constant(1 / (sigma_r * sigma_r));
  return d.asDiagonal();
}

Graph odometryGraph(std::size_t keyframes, bool tie_hanging) {
  constexpr std::size_t kHanging = 11, kEvery = 10, kBack = 50;
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, 1.0);
  const auto truth = [](std::size_t k) {  // 10 cm a step along a winding path, turning 2 deg a step
    const double a = 0.035 * static_cast<double>(k);
    Isometry3 T = Isometry3::Identity();
    T.linear() = Eigen::AngleAxisd(a, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    T.translation() = Eigen::Vector3d(3 * std::sin(a), 3 * (1 - std::cos(a)), 0.2 * std::sin(0.1 * a));
    return T;
  };
  const auto measured = [&](const Isometry3& T, double sigma_t, double sigma_r) {
    Vector6d xi;
    for (int j = 0; j < 3; ++j) xi(j) = sigma_t * noise(rng), xi(j + 3) = sigma_r * noise(rng);
    return gasp::expLeft(xi) * T;
  };
  const double st = 0.01, sr = 0.5 * M_PI / 180;
  Graph g;
  std::vector<std::size_t> node_of(keyframes);
  std::vector<Isometry3> true_pose(keyframes);
  for (std::size_t k = 0; k < keyframes; ++k) {
    true_pose[k] = truth(k);
    node_of[k] = g.T_world_node.size();
    if (k == 0) {
      g.T_world_node.push_back(true_pose[0]);
    } else {
      PoseConstraint c;
      c.from = node_of[k - 1];
      c.to = node_of[k];
      c.T_from_to = measured(true_pose[k - 1].inverse() * true_pose[k], st, sr);
      c.information = information(st, sr);
      g.edges.push_back(c);
      g.T_world_node.push_back(true_pose[k]);
    }
    for (std::size_t h = 1; h <= kHanging; ++h) {  // the frames tracked against keyframe k
      PoseConstraint c;
      c.from = node_of[k];
      c.to = g.T_world_node.size();
      Isometry3 step = Isometry3::Identity();
      step.translation() = Eigen::Vector3d(0.1 * static_cast<double>(h) / (kHanging + 1), 0, 0);
      c.T_from_to = measured(step, st, sr);
      c.information = information(st, sr);
      g.edges.push_back(c);
      g.T_world_node.push_back(g.T_world_node[c.from] * c.T_from_to);
      if (tie_hanging && k > 0) {
        PoseConstraint tie;
        tie.from = node_of[k - 1];
        tie.to = c.to;
        tie.T_from_to = g.T_world_node[tie.from].inverse() * g.T_world_node[tie.to];
        tie.information = 1e-12 * information(st, sr);
        g.edges.push_back(tie);
      }
    }
    if (k >= kBack && k % kEvery == 0) {
      PoseConstraint c;
      c.from = node_of[k - kBack];
      c.to = node_of[k];
      c.T_from_to = measured(true_pose[k - kBack].inverse() * true_pose[k], 0.001, 0.0005);
      c.information = information(0.001, 0.0005);
      c.loop_closure = true;
      g.edges.push_back(c);
    }
  }
  return g;
}

/// The graph of `keyframes` optimised up to its last closure, and that closure: the start of the
/// optimisation timed.
struct Step {
  std::vector<Isometry3> T_world_node;
  std::vector<PoseConstraint> edges;
};

Step lastStep(std::size_t keyframes, bool tie_hanging) {
  Graph g = odometryGraph(keyframes, tie_hanging);
  std::size_t last = g.edges.size();
  while (last > 0 && !g.edges[last - 1].loop_closure) --last;
  if (last == 0) throw std::invalid_argument("bench_pose_graph: no loop closure in a graph of so few keyframes");
  PoseConstraint closure = g.edges[--last];
  g.edges.erase(g.edges.begin() + static_cast<std::ptrdiff_t>(last));
  // The graph before, optimised from near its optimum (the truth), as a job's earlier
  // optimisations keep it.
  Step s{gasp::optimizePoseGraph(g.T_world_node, g.edges).T_world_node, std::move(g.edges)};
  s.edges.push_back(closure);
  return s;
}

void optimiseAfterAClosure(benchmark::State& state, bool tie_hanging) {
  const Step s = lastStep(static_cast<std::size_t>(state.range(0)), tie_hanging);
  gasp::PoseGraphResult r;
  for (auto _ : state) {
    r = gasp::optimizePoseGraph(s.T_world_node, s.edges);
    benchmark::DoNotOptimize(r);
  }
  if (!r.converged) state.SkipWithError(r.message.c_str());
  state.counters["nodes"] = static_cast<double>(s.T_world_node.size());
  state.counters["optimised"] = static_cast<double>(s.T_world_node.size() - r.placed_nodes);
  state.counters["iterations"] = r.iterations;
}

void BM_OptimisePoseGraph(benchmark::State& state) { optimiseAfterAClosure(state, false); }
void BM_OptimiseEveryNode(benchmark::State& state) { optimiseAfterAClosure(state, true); }
BENCHMARK(BM_OptimisePoseGraph)->Arg(100)->Arg(1000)->Arg(10000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_OptimisePoseGraph)->Arg(50000)->Iterations(3)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_OptimiseEveryNode)->Arg(100)->Arg(1000)->Arg(10000)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
