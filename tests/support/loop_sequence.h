#pragma once
// A synthetic sequence that closes a loop, with exact ground truth: the simulator's room seen by a
// camera circling a pose of its path (tests of gasp::slam and gasp::graphslam).
#include <algorithm>
#include <cmath>
#include <vector>

#include "gasp/core/pose.h"
#include "gasp/sim/camera_path.h"
#include "gasp/sim/noise_model.h"
#include "gasp/sim/renderer.h"
#include "gasp/sim/simulation.h"

namespace gasp::test {

/// The simulator's room, and a camera that circles 0.3 m around a pose of its path looking at a
/// point 3 m ahead, at 5 Hz, coming back to where it began. With `look_away`, the frames
/// listed look 90 degrees to the right (nothing in common with the others).
struct LoopSequence {
  std::vector<gasp::Isometry3> T_world_camera;
  std::vector<cv::Mat> depth;
  std::vector<double> timestamps;
  gasp::CameraIntrinsics K;
};

inline const gasp::sim::Simulation& room() {
  static const gasp::sim::Simulation sim{gasp::sim::SimulationOptions{}};
  return sim;
}

inline LoopSequence circleSequence(int frames, const std::vector<int>& look_away = {}) {
  const auto& sim = room();
  LoopSequence s;
  s.K = sim.options().intrinsics;
  // From the path's frame 45 (in its roll), looking 3 m ahead: the room's clutter fills the view.
  const gasp::Isometry3 start = sim.path().poses.at(45).T_world_camera;
  const Eigen::Vector3d p0 = start.translation(), target = start * Eigen::Vector3d(0, 0, 3.0);
  const double r = 0.3;
  for (int i = 0; i < frames; ++i) {
    const double a = 2 * M_PI * i / frames;
    const Eigen::Vector3d p = p0 + r * Eigen::Vector3d(std::cos(a) - 1, std::sin(a), 0);
    const bool turned = std::find(look_away.begin(), look_away.end(), i) != look_away.end();
    const Eigen::Vector3d away = p + Eigen::AngleAxisd(-M_PI / 2, Eigen::Vector3d::UnitZ()) * (target - p);
    const gasp::Isometry3 T = gasp::sim::lookAt(p, turned ? away : target);
    const auto rendered = gasp::sim::renderFrame(sim.scene(), s.K, T, 0);
    s.depth.push_back(gasp::sim::sensorDepth(rendered, sim.options().noise, s.K, 7, i));
    s.T_world_camera.push_back(T);
    s.timestamps.push_back(1000.0 + i / 5.0);
  }
  return s;
}

}  // namespace gasp::test
