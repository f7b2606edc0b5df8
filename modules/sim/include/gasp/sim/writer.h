#pragma once
/// \file writer.h Writes a simulated sequence as a TUM RGB-D style folder.
///
/// Layout of DIR:
///   depth/<timestamp>.png   16-bit depth, value / 5000 = metres, 0 = missing
///   labels/<timestamp>.png  16-bit ground-truth surface id of each pixel with valid depth (0 elsewhere)
///   depth.txt               `timestamp depth/<timestamp>.png`
///   groundtruth.txt         TUM trajectory of the optical camera frame (T_world_camera)
///   intrinsics.txt          CameraIntrinsics::save() format (read by gasp::TumDataset)
///   segments.txt            `name first_frame last_frame first_timestamp last_timestamp`
///   surfaces.txt            `surface_id object shape face`
///   scene.txt               `key: value` lines: scene, seed, frames, noise parameters, ...
/// Same options give byte-identical files.
#include <string>
#include <vector>

#include "gasp/sim/simulation.h"

namespace gasp::sim {

/// What writeSimulation() wrote.
struct SimulationSummary {
  std::string out_dir;
  std::string scene;
  int frames = 0;
  std::uint64_t seed = 0;
  double valid_pixel_share = 0.0;  ///< valid depth pixels / all pixels over the sequence
  std::vector<TrajectorySegment> segments;
};

/// Timestamp as used in file names and lists: fixed, 6 decimals ("1000.033333").
std::string formatTimestamp(double t);

/// Simulates and writes the sequence into out_dir (created if needed; the files of an earlier
/// simulation there are overwritten). Throws gasp::Error for bad options, when out_dir cannot be
/// created or written, or when it holds a depth.txt the simulator did not write (a real TUM
/// folder is never overwritten).
SimulationSummary writeSimulation(const SimulationOptions& options, const std::string& out_dir);

}  // namespace gasp::sim
