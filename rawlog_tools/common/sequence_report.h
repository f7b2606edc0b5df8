#pragma once
/// \file sequence_report.h What gasp-odometry and gasp-slam print and write about a sequence.
#include <cstddef>
#include <string>
#include <vector>

#include "gasp/core/tum_trajectory.h"
#include "gasp/odometry/odometry.h"

namespace gasp::tools {

/// One line per frame: index,timestamp,tracked,keyframe,reference,patches,inliers,deskewed,
/// segmentation_ms,registration_ms,scene_change,reason. Throws gasp::Error when it cannot be written.
void writeFramesCsv(const std::string& path, const std::vector<OdometryFrame>& frames);

/// Prints frames:, tracked:, scene_changes: (with the first ten such frames), keyframes:,
/// graph_components: (the odometry's pieces) and
/// median_ms_per_frame: (the median of each frame's segmentation + registration, then the two
/// stages' own medians).
void printOdometrySummary(const DepthOdometry& odometry);

/// Prints `<prefix>ate_rmse_m:` and `<prefix>rpe_1s_rmse:` of `estimate` against `ground_truth`
/// (TUM's definitions, gasp/eval), or why they cannot be computed: among them, fewer than two
/// `tracked` frames (the first frame and the predicted poses of lost frames measure nothing).
void printEvaluation(const Trajectory& ground_truth, const Trajectory& estimate, std::size_t tracked,
                     const std::string& prefix = "");

}  // namespace gasp::tools
