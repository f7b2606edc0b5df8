// Speed of a LiDAR pair with no prior (registerRangeScans: both sweeps binned and segmented, the
// pair pipeline, the returns' point-to-plane rounds) on simulated sweeps of 16, 32 and 64 lasers
// in the furnished room, and on MRPT's real VLP-16 sweep against itself moved.
//   build/ci/bin/bench_lidar_pair [--threads T] [--params FILE] [google benchmark flags]
// TBB runs with T threads (default 2). --params FILE: the params file's pair sections made a
// LiDAR's by its lidar section (lidarPairParams), as bench_lidar_sequence takes them; the
// defaults otherwise. Afterwards a table gives the median time of each part and the pose error
// of every pair.
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/obs/CObservationRotatingScan.h>
#include <mrpt/serialization/CArchive.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "gasp/core/error.h"
#include "gasp/params/params_file.h"
#include "gasp/pipeline/range_view.h"
#include "gasp/rawlog/range_scan.h"
#include "gasp/sim/lidar.h"
#include "gasp/sim/scene.h"

namespace {

constexpr const char* kRealSweep = "/usr/share/mrpt/datasets/rot_scan_velodyne.rawlog";

struct LidarPair {
  std::string name;
  gasp::RangeScan source, target;
  gasp::Isometry3 T_target_source;
};

/// The second sweep 0.6 m ahead, 0.15 m aside and turned 37 deg: bins out of step with the first's.
gasp::Isometry3 benchMotion() {
  gasp::Isometry3 T = gasp::Isometry3::Identity();
  T.linear() = Eigen::AngleAxisd(37.0 * M_PI / 180, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(0.6, 0.15, 0.0);
  return T;
}

std::vector<LidarPair> makePairs() {
  std::vector<LidarPair> pairs;
  const gasp::sim::Scene room = gasp::sim::makeScene("room");
  gasp::Isometry3 T_world_a = gasp::Isometry3::Identity();
  T_world_a.translation() = Eigen::Vector3d(0.6, 0.0, 1.0);
  const gasp::Isometry3 T_world_b = T_world_a * benchMotion();
  for (const int lasers : {16, 32, 64}) {
    const gasp::sim::LidarSensor sensor = gasp::sim::lidarSensor(lasers);
    pairs.push_back({"sim " + std::to_string(lasers) + " lasers", gasp::sim::simulateLidarScan(room, sensor, T_world_a, 1, 0),
                     gasp::sim::simulateLidarScan(room, sensor, T_world_b, 1, 1), T_world_b.inverse() * T_world_a});
  }
  if (std::filesystem::exists(kRealSweep)) {
    mrpt::io::CFileGZInputStream in(kRealSweep);
    auto archive = mrpt::serialization::archiveFrom(in);
    const auto scan = std::dynamic_pointer_cast<mrpt::obs::CObservationRotatingScan>(archive.ReadObject());
    if (scan) {
      const gasp::RangeScan real = gasp::rangeScanFrom(*scan);
      const gasp::Isometry3 T = benchMotion().inverse();  // the sweep seen from the moved sensor
      pairs.push_back({"real VLP-16 (MRPT), moved", real, gasp::movedScan(real, T), T});
    }
  } else {
    std::printf("%s not found (package mrpt-common): the real sweep is left out\n", kRealSweep);
  }
  return pairs;
}

std::vector<LidarPair>& pairs() {
  static std::vector<LidarPair> p = makePairs();
  return p;
}

struct Run {
  double segmentation = 0, pipeline = 0, returns = 0, sweep_motion = 0, total = 0, error_cm = -1, error_deg = -1;
  bool success = false;
};

gasp::PairParams& pairParams() {
  static gasp::PairParams p = gasp::lidarPairParams();
  return p;
}

Run runPair(const LidarPair& p) {
  const auto t0 = std::chrono::steady_clock::now();
  const gasp::RangePairResult r = gasp::registerRangeScans(p.source, p.target, pairParams());
  Run run;
  run.total = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  run.segmentation = r.segmentation_ms;
  run.returns = r.pair.timings.returns_ms;
  run.sweep_motion = r.pair.timings.sweep_motion_ms;
  run.pipeline = run.total - run.segmentation - run.returns - run.sweep_motion;
  run.success = r.pair.pose.success;
  if (run.success) {
    const gasp::Isometry3 e = p.T_target_source.inverse() * r.pair.pose.T_target_source;
    run.error_cm = 100.0 * e.translation().norm();
    run.error_deg = Eigen::AngleAxisd(e.linear()).angle() * 180.0 / M_PI;
  }
  return run;
}

std::map<std::string, std::vector<Run>>& runs() {
  static std::map<std::string, std::vector<Run>> r;
  return r;
}

void BM_LidarPair(benchmark::State& state) {
  const LidarPair& p = pairs()[static_cast<std::size_t>(state.range(0))];
  state.SetLabel(p.name + ", " + std::to_string(p.source.returnCount()) + " returns");
  for (auto _ : state) runs()[p.name].push_back(runPair(p));
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  int threads = 2;
  std::vector<char*> rest;
  for (int i = 0; i < argc; ++i) {
    if (std::strcmp(argv[i], "--threads") == 0 && i + 1 < argc) {
      threads = std::max(1, std::atoi(argv[++i]));
      continue;
    }
    if (std::strcmp(argv[i], "--params") == 0 && i + 1 < argc) {
      try {
        const gasp::SlamParams file = gasp::readParamsFile(argv[++i]);
        pairParams() = gasp::lidarPairParams(file.lidar, file.odometry.pair);
      } catch (const gasp::Error& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
      }
      continue;
    }
    rest.push_back(argv[i]);
  }
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
  for (std::size_t i = 0; i < pairs().size(); ++i)
    benchmark::RegisterBenchmark("BM_LidarPair", BM_LidarPair)->Arg(static_cast<int64_t>(i))->Unit(benchmark::kMillisecond)->MinTime(2.0);
  int rest_argc = static_cast<int>(rest.size());
  benchmark::Initialize(&rest_argc, rest.data());
  benchmark::RunSpecifiedBenchmarks();
  std::printf("\n| Pair | Returns | Segmentation [ms] | Pipeline [ms] | Returns' rounds [ms] | Sweep motion [ms] | Total [ms] | Error |\n");
  std::printf("|---|---|---|---|---|---|---|---|\n");
  for (const LidarPair& p : pairs()) {
    const std::vector<Run>& r = runs()[p.name];
    if (r.empty()) continue;
    std::vector<double> seg, pipe, ret, motion, total;
    for (const Run& x : r)
      seg.push_back(x.segmentation), pipe.push_back(x.pipeline), ret.push_back(x.returns), motion.push_back(x.sweep_motion),
          total.push_back(x.total);
    char error[64] = "no estimate";
    if (r.front().success) std::snprintf(error, sizeof error, "%.2f cm, %.3f deg", r.front().error_cm, r.front().error_deg);
    std::printf("| %s | %zu | %.1f | %.1f | %.1f | %.1f | %.1f | %s |\n", p.name.c_str(), p.source.returnCount(), median(seg),
                median(pipe), median(ret), median(motion), median(total), error);
  }
  return 0;
}
