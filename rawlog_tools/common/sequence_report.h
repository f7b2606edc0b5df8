#pragma once
/// \file sequence_report.h What gasp-odometry and gasp-slam print and write about a sequence.
#include <cstddef>
#include <ostream>
#include <string>
#include <vector>

#include "gasp/core/output_file.h"
#include "gasp/core/tum_trajectory.h"
#include "gasp/odometry/odometry.h"
#include "frames_ahead.h"

namespace gasp::tools {

/// One line per frame: index,timestamp,tracked,keyframe,reference,patches,inliers,deskewed,
/// segmentation_ms,registration_ms,scene_change,reason, into `out` (RunOutputs' file; its
/// commit() checks the writes).
void writeFramesCsv(std::ostream& out, const std::vector<OdometryFrame>& frames);

/// The trajectory header of a program's output, with the partial-result line when the input
/// ended with an error ("PARTIAL: ..." as a second '#' line).
std::string trajectoryHeader(const std::string& what, const SequenceEnd& end);

/// When the input ended with an error: "partial: N frames (the input ended with an error: MSG);
/// the outputs hold these frames only" on stdout and "error: MSG" on stderr. Returns the exit code
/// 1 then, else -1.
int reportPartial(const SequenceEnd& end);

/// Writes the graph as MRPT's text (VERTEX3 / EDGE3, CNetworkOfPoses::writeAsText) into the
/// file and commits it.
template <class Graph>
void writeGraph(OutputFile& file, const Graph& graph) {
  graph.writeAsText(file.stream());
  file.commit();
}

/// Prints frames:, tracked:, scene_changes: (with the first ten such frames), keyframes:,
/// graph_components: (the odometry's pieces) and
/// median_ms_per_frame: (the median of each frame's segmentation + registration, then the two
/// stages' own medians).
void printOdometrySummary(const DepthOdometry& odometry);

/// Prints wall_time_s: (of the run over the frames, reading included), fps: (frames per second of
/// it) and real_time_factor: (the sequence's duration -- its timestamps' span plus one median
/// frame interval, summed over the sessions -- over the wall time: >= 1 keeps up with the sensor).
void printThroughput(const std::vector<OdometryFrame>& frames, double wall_s);

/// Prints `<prefix>ate_rmse_m:` and `<prefix>rpe_1s_rmse:` of `estimate` against `ground_truth`
/// (TUM's definitions, gasp/eval), or why they cannot be computed: among them, fewer than two
/// `tracked` frames (the first frame and the predicted poses of lost frames measure nothing).
void printEvaluation(const Trajectory& ground_truth, const Trajectory& estimate, std::size_t tracked,
                     const std::string& prefix = "");

}  // namespace gasp::tools
