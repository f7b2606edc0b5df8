#pragma once
/// \file tum_trajectory.h TUM trajectory files (`timestamp tx ty tz qx qy qz qw`) and timestamp
/// association as in the TUM benchmark's associate.py.
#include <optional>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "gasp/core/pose.h"

namespace gasp {

struct StampedPose {
  double timestamp = 0.0;  ///< seconds
  Isometry3 T_world_camera = Isometry3::Identity();
};

/// Poses sorted by timestamp.
using Trajectory = std::vector<StampedPose>;

/// Reads a TUM trajectory; '#' lines and blank lines are skipped. Throws gasp::Error naming the
/// file and line for a line without exactly 8 finite numbers or with a zero quaternion, and for a
/// missing file. The result is sorted by timestamp; duplicated timestamps are an error.
Trajectory readTumTrajectory(const std::string& path);

/// Writes a TUM trajectory with an optional '#' header line (stamps with 6 decimals, poses with 9)
/// to `out`; the caller checks the stream (OutputFile::commit()).
void writeTumTrajectory(std::ostream& out, const Trajectory& trajectory, const std::string& header = "");

/// The same into the file `path`, whole or not at all (gasp/core/output_file.h); throws
/// gasp::Error naming the file when it cannot be written.
void writeTumTrajectory(const std::string& path, const Trajectory& trajectory,
                        const std::string& header = "");

/// Index of the pose nearest in time to t in a sorted trajectory, if within max_dt seconds.
std::optional<std::size_t> findNearest(const Trajectory& trajectory, double t, double max_dt);

/// Index of the nearest element of a sorted vector (TUM evaluate_rpe.py's find_closest_index).
std::size_t findClosestIndex(const std::vector<double>& sorted, double t);

/// One-to-one association of two timestamp lists exactly as TUM's associate.py: every pair with
/// |a - (b + offset)| < max_dt is a candidate; candidates are taken greedily by increasing
/// difference, each stamp used once. Returns index pairs (into a, into b) sorted by a's stamp.
std::vector<std::pair<std::size_t, std::size_t>> associateTimestamps(
    const std::vector<double>& a, const std::vector<double>& b, double max_dt, double offset = 0.0);

}  // namespace gasp
