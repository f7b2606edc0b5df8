#pragma once
/// \file sessions.h gasp-slam's sessions: several inputs (TUM folders, rawlogs, or frame ranges of
/// them), each tracked on its own and joined into one map where they share places
/// (DepthSlam::startSession()); their outputs and the report of which were joined.
#include <cstddef>
#include <ostream>
#include <string>
#include <vector>

#include "gasp/core/tum_trajectory.h"
#include "gasp/rawlog/depth_sequence.h"
#include "gasp/slam/depth_slam.h"
#include "frames_ahead.h"

namespace gasp::tools {

/// One session's input: `spec` as given, PATH[@FIRST-LAST] (PATH a TUM folder or a rawlog;
/// FIRST-LAST the input's frames used, inclusive, LAST optional), and the sequence options with
/// the shared ones (`shared`: --every, --sensor, --intrinsics, ...) applied. Throws gasp::Error
/// naming the spec for a range that is not FIRST-LAST with FIRST <= LAST.
DepthSequenceOptions sessionOptions(const std::string& spec, const DepthSequenceOptions& shared);

/// The output path of session `session` (0-based) of `count`: `path` itself for one session,
/// else with ".session<N>" (N from 1) inserted before its extension (traj.txt -> traj.session1.txt).
std::string sessionPath(const std::string& path, std::size_t session, std::size_t count);

/// What became of one session.
struct SessionRun {
  std::string input;        ///< DepthSequence::describe(), with the frame range when given
  std::size_t first_frame = 0;  ///< its first frame in the graph
  std::size_t frames = 0;
  std::size_t tracked = 0;
  SequenceEnd end;
  Trajectory ground_truth;  ///< its reference (empty: none)
};

/// The sessions joined: maps[m] lists the sessions (ascending) that constraints link, directly or
/// through others, sessionLinks() being the constraints between each two; a map's frame is the
/// world its first session started in.
std::vector<std::vector<std::size_t>> sessionMaps(const std::vector<std::vector<std::size_t>>& links);

/// The session's frames of the whole trajectory.
Trajectory sessionTrajectory(const Trajectory& all, const SessionRun& run);

/// Prints the report (sessions:, one session line each with its map and its links, one map line
/// each) and, when the sessions have references, each session's ATE aligned on its own and in its
/// map's frame (one alignment over all of the map's sessions: their references must share one
/// world, as the pieces of one sequence do). Writes the same as YAML into `yaml` when given.
void reportSessions(const std::vector<SessionRun>& runs, const DepthSlam& slam, const Trajectory& trajectory,
                    const std::vector<std::string>& trajectory_paths, std::ostream* yaml);

}  // namespace gasp::tools
