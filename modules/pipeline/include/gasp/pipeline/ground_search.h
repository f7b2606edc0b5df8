#pragma once
/// \file ground_search.h A pose hypothesis for two LiDAR sweeps that association gives none for.
///
/// Where the sweeps' patches repeat too little to be associated (a street seen from points metres
/// apart: the laser rows cross a facade elsewhere, so its patches are cut elsewhere), the sweeps'
/// geometry still holds the answer. Both see the ground: aligning the two ground planes fixes
/// height, roll and pitch. What is left -- a yaw and a translation on the ground -- is searched
/// exhaustively over the returns on upright surfaces (facades, poles, cars, walls) projected onto
/// the ground, the 2D map of classical scan matching: a coarse vote over every yaw and every
/// offset, then the best peaks refined on a finer grid. The search proposes the best pose and the
/// best distinct runner-up; registerViews() refines both and judges them as it judges RANSAC's
/// hypothesis and its alternative (dense rounds, certificate, uniqueness, symmetry), so the
/// search decides nothing by itself.
#include <optional>
#include <string>

#include "gasp/core/pose.h"

namespace gasp {

class SweepReturns;  // returns_stage.h

struct GroundSearchParams {
  bool enabled = true;  ///< registerViews() runs it on sweeps (both views carry their returns)
  /// The ground: the cells between rows (a return, the next row's, its row's neighbours) facing up
  /// within max_ground_tilt_deg of the sensor's axis, on the most populated height (bins of
  /// ground_bin_m, weighted by cell area), then a plane fitted to those near it.
  double max_ground_tilt_deg = 30.0;
  double ground_bin_m = 0.1;
  /// Upright surfaces: returns whose normal is within max_upright_tilt_deg of the ground plane,
  /// at least min_height_m above the ground and within max_range_m on it.
  double max_upright_tilt_deg = 30.0;
  double min_height_m = 0.3;
  double max_range_m = 40.0;
  /// The search: yaws every coarse_yaw_deg and offsets up to max_offset_m voted on cells of
  /// coarse_cell_m; the best `peaks` distinct peaks refined on cells of fine_cell_m over
  /// +-coarse_yaw_deg and +-coarse_cell_m, then on a quarter of the steps (the coarse vote ranks
  /// roughly; the refined scores decide).
  double coarse_cell_m = 1.0;
  double coarse_yaw_deg = 2.0;
  double max_offset_m = 30.0;
  double fine_cell_m = 0.25;
  int peaks = 12;
  /// Two peaks are distinct when their offsets differ by more than distinct_m or their yaws by
  /// more than distinct_deg.
  double distinct_m = 2.0;
  double distinct_deg = 10.0;
  /// Each view needs this many upright cells of fine_cell_m, and the best pose must land this
  /// share of the source's on the target's.
  int min_cells = 50;
  double min_score = 0.2;
};

/// Throws gasp::Error naming the first parameter out of its range.
void validate(const GroundSearchParams& params);

struct GroundSearchResult {
  bool found = false;
  std::string reason;  ///< why not, when not found
  Isometry3 T_target_source = Isometry3::Identity();
  double score = 0.0;  ///< share of the source's upright cells the pose lands on the target's
  /// The best pose of a distinct peak, when one scored at least min_score.
  std::optional<Isometry3> runner_up;
  double runner_up_score = 0.0;
  int source_cells = 0, target_cells = 0;
  double ms = 0.0;
};

/// The search between two sweeps' returns (sensor frames). Never throws for data.
GroundSearchResult groundSearch(const SweepReturns& source, const SweepReturns& target, const GroundSearchParams& params);

/// The search's score of one pose (the share of the source's upright cells it lands on the
/// target's); 0 where either sweep has no ground or no upright cell. For diagnostics.
double groundSearchScore(const SweepReturns& source, const SweepReturns& target, const Isometry3& T_target_source,
                         const GroundSearchParams& params);

}  // namespace gasp
