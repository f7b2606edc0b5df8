#pragma once
/// \file simulation.h A scene, a camera path and the sensor model together: frames on demand.
#include <cstdint>
#include <string>
#include <vector>

#include "gasp/core/camera_intrinsics.h"
#include "gasp/sim/camera_path.h"
#include "gasp/sim/noise_model.h"
#include "gasp/sim/object_move.h"
#include "gasp/sim/renderer.h"
#include "gasp/sim/scene.h"

namespace gasp::sim {

/// Everything that determines a simulated sequence.
struct SimulationOptions {
  std::string scene = "room";  ///< a name of sceneNames()
  int frames = 60;             ///< number of frames (>= kMinPathFrames)
  std::uint64_t seed = 1;      ///< noise seed
  KinectNoiseModel noise;      ///< KinectNoiseModel::exact() for no noise
  CameraIntrinsics intrinsics = CameraIntrinsics::rosDefault();  ///< 525/525/319.5/239.5, 640x480
  double start_time_s = 1000.0;  ///< timestamp of frame 0 [s]
  double rate_hz = 30.0;         ///< frame rate [Hz]
  std::vector<ObjectMove> moves;  ///< objects moved between frames (none: a static scene)
};

/// One simulated frame.
struct SimulatedFrame {
  int index = 0;
  double timestamp = 0.0;  ///< [s]
  Isometry3 T_world_camera = Isometry3::Identity();  ///< ground truth (optical frame)
  cv::Mat depth;   ///< CV_32FC1 sensor depth [m], multiples of 1/5000 m, 0 = missing
  /// CV_16UC1 ground-truth surface id of each pixel with valid depth; 0 where depth is missing.
  cv::Mat labels;
};

/// Name of the object addOccluder() adds.
inline const char* const kOccluderName = "occluder";

/// Adds a person-sized box (0.25 x 0.4 x 1.8 m, standing on the floor) about 1 m in front of the
/// camera's pose at the end of the occluder_appears segment, visible from the segment's middle
/// frame (so absent in its first frame and present in its last).
void addOccluder(Scene& scene, const CameraPath& path);

/// A simulated sequence. Frames are computed on demand; each depends only on (options, index).
class Simulation {
 public:
  /// Builds the scene (plus the occluder unless the scene is degenerate, and the moves) and the
  /// camera path. Throws gasp::Error for an unknown scene, too few frames, invalid
  /// noise/intrinsics or an invalid move (applyObjectMoves).
  explicit Simulation(const SimulationOptions& options);

  const SimulationOptions& options() const { return options_; }
  const Scene& scene() const { return scene_; }
  const CameraPath& path() const { return path_; }
  int size() const { return path_.size(); }

  /// Ground-truth rendering of frame i (no sensor model).
  RenderedFrame render(int i) const;
  /// Frame i with the sensor model applied. Throws gasp::Error for i out of range.
  SimulatedFrame frame(int i) const;

 private:
  void checkIndex(int i) const;

  SimulationOptions options_;
  Scene scene_;
  CameraPath path_;
};

}  // namespace gasp::sim
