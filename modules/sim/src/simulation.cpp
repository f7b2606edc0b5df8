#include "gasp/sim/simulation.h"

#include <cmath>

#include "gasp/core/error.h"

namespace gasp::sim {

void addOccluder(Scene& scene, const CameraPath& path) {
  const TrajectorySegment& seg = path.segment(kOccluderAppears);
  const Isometry3& T_world_camera = path.poses.at(static_cast<std::size_t>(seg.last_frame)).T_world_camera;
  // 1 m ahead along the optical axis, slightly to the right in the image, standing on the floor.
  const Eigen::Vector3d p = T_world_camera * Eigen::Vector3d(0.15, 0.0, 1.0);
  const Eigen::Vector3d forward = T_world_camera.linear().col(2);
  const double yaw_deg = std::atan2(forward.y(), forward.x()) * 180.0 / EIGEN_PI;
  const int visible_from = seg.first_frame + (seg.last_frame - seg.first_frame + 1) / 2;
  scene.add(kOccluderName, Box{Eigen::Vector3d(0.125, 0.2, 0.9)}, placeAt(p.x(), p.y(), 0.9, yaw_deg),
            visible_from);
}

Simulation::Simulation(const SimulationOptions& options) : options_(options) {
  options_.noise.validate();
  options_.intrinsics.validate();
  scene_ = makeScene(options_.scene);
  CameraPathOptions path_options;
  path_options.frames = options_.frames;
  path_options.start_time_s = options_.start_time_s;
  path_options.rate_hz = options_.rate_hz;
  if (!scene_.walk.empty())
    path_ = makeWalkPath(scene_.walk, path_options);
  else
    path_ = scene_.hand_held ? makeHandHeldPath(*scene_.hand_held, path_options) : makeCameraPath(path_options);
  if (!scene_.degenerate && scene_.walk.empty()) addOccluder(scene_, path_);
  applyObjectMoves(scene_, options_.moves, path_.size());
}

void Simulation::checkIndex(int i) const {
  if (i < 0 || i >= size())
    throw Error("simulation: frame index " + std::to_string(i) + " out of range [0, " +
                std::to_string(size()) + ")");
}

RenderedFrame Simulation::render(int i) const {
  checkIndex(i);
  return renderFrame(scene_, options_.intrinsics, path_.poses[static_cast<std::size_t>(i)].T_world_camera, i);
}

SimulatedFrame Simulation::frame(int i) const {
  const RenderedFrame gt = render(i);
  SimulatedFrame f;
  f.index = i;
  f.timestamp = path_.poses[static_cast<std::size_t>(i)].timestamp;
  f.T_world_camera = path_.poses[static_cast<std::size_t>(i)].T_world_camera;
  f.depth = sensorDepth(gt, options_.noise, options_.intrinsics, options_.seed, i);
  f.labels = cv::Mat::zeros(gt.surface_id.size(), CV_16UC1);
  gt.surface_id.copyTo(f.labels, f.depth > 0.0f);
  return f;
}

}  // namespace gasp::sim
