#pragma once
/// \file sweep_motion.h Stage 8, for two timed LiDAR sweeps: each sweep's own motion while it was
/// taken, estimated with the pose between their starts.
///
/// A rotating LiDAR fires its columns one after the other over a sweep (RangeScan::sweep_duration_s),
/// so a sensor that moves meanwhile sees the scene from a different pose at every column, and a
/// rigid pose between two such sweeps fits their skew, not the scene. Each sweep is modelled as
/// moving at a constant twist xi (in its own frame): its column c fired at t = columnTime(c) from
/// the pose exp(t xi) relative to its start, so a return p(t) lies at p(0) = exp([w t]) p(t) + v t
/// (deskewSweep(), range_scan.h). From a claimed pose, the returns' point-to-plane rounds
/// (returns_stage.h) solve for T_target_source between the sweeps' start poses and both twists
/// together (18 unknowns), with a zero-mean prior on each twist of a robot's plausible motion
/// (speed_sigma_mps, rate_sigma_radps) that fixes what the pair cannot observe: two sweeps that see
/// the scene from nearly the same place observe the difference of their twists; a motion common
/// to both skews them alike and shows only in the wedge between their seams (the sweeps' first
/// and last columns), or not at all for a common vertical speed.
///
/// The verdict is a score test at rest, which costs one round of terms at the claimed pose: the
/// twists' gradient at zero, less what the pose absorbs (the efficient score), summed per sector
/// of the source sweep's firing time, and Hotelling's test that the sectors' mean score is zero
/// (F of 12 and K - 12 degrees of freedom over K sectors, at a false-alarm rate). Each sector
/// counts once, however many returns it holds: residuals of one surface are correlated, and a
/// test that took every return as independent evidence finds "motion" in still sweeps' small
/// modelling errors. Still sweeps end there; moving ones go on to the rounds, then are deskewed
/// with their twists and registered again (registerViews()).
///
/// A pair the test takes for still keeps its pose only while that pose is determined whatever
/// motion the test cannot exclude: with both twists unknown under their prior (the normal
/// equations' Schur complement at the claimed pose), the pose's standard deviation must stay
/// within the returns' last gate (the distance beyond which a return is not taken as on the
/// surface: 4 range sigmas), its rotation's measured as the displacement it gives at the terms'
/// RMS range. Where a motion common to both sweeps (which skews them alike) can move the pose
/// further, which returns match is itself in doubt, and the pair has no estimate: such sweeps,
/// rolling alike, had a cost minimum centimetres and degrees from the truth.
#include <string>

#include "gasp/core/pose.h"
#include "gasp/core/rolling_shutter.h"

namespace gasp {

class SweepReturns;
struct ReturnsRefineParams;
struct RefinementParams;

struct SweepMotionParams {
  /// Estimate the motion of two sweeps whose columns carry their times (sweepTimed()).
  bool enabled = true;
  /// The twists' prior: zero mean, these standard deviations per axis [m/s, rad/s], a walking or
  /// driving robot's speed and turn rate. The pair's own data outweigh it wherever they observe
  /// the motion; it holds what they do not (chiefly both sweeps' common vertical speed).
  double speed_sigma_mps = 2.0;
  double rate_sigma_radps = 1.0;
  /// The score test's sectors of the source sweep (equal spans of firing time; 128 of a full turn
  /// are 2.8 deg wide) and its false-alarm rate: still sweeps are taken as moving this often.
  int sectors = 128;
  double false_alarm = 0.001;
};

/// Throws gasp::Error naming the first parameter out of its range.
void validate(const SweepMotionParams& params);

/// The verdict of stage 8.
struct SweepMotion {
  /// The score test found motion and the rounds converged to a pose and twists.
  bool estimated = false;
  /// Estimated: the sweeps are to be deskewed with the twists (registerViews() does).
  bool moving = false;
  Isometry3 T_target_source = Isometry3::Identity();  ///< between the sweeps' start poses
  CameraTwist source_twist, target_twist;             ///< each in its own sensor frame
  double score_f = 0.0;      ///< the score test's F statistic at the claimed pose
  double score_bound = 0.0;  ///< its bound: F(12, sectors - 12) at 1 - false_alarm
  int sectors = 0;           ///< the source sweep's sectors that had terms
  int terms = 0;                ///< point-to-plane terms of the last round
  double rms_residual_m = 0.0;  ///< their RMS residual [m]
  double ms = 0.0;              ///< wall time of the estimate (not of the second registration)
  std::string reason;           ///< why not moving: at rest (the statistics) or not estimated
  /// At rest: the claimed pose's largest standard deviation with both twists unknown under their
  /// prior, of translation [m] and of rotation times the terms' RMS range [m] (per term, as the
  /// solver's information), and whether both are within the returns' last gate. false: the pose
  /// as read is not determined, and the pair has no estimate (registerViews()).
  double free_motion_sigma_m = 0.0;
  double free_motion_rotation_m = 0.0;
  bool determined = true;
};

/// The rounds of stage 8 from T_target_source (both sweeps' returns, their column times from the
/// scans they were made of): gates, steps and convergence as refineOnReturns() (`returns`), the
/// robust loss and noise of `solver`. moving false with a reason when the sweeps are at rest, a
/// sweep carries no column times, fewer than 18 terms remain, or the solve fails. Throws
/// gasp::Error for invalid params.
SweepMotion estimateSweepMotion(const SweepReturns& source, const SweepReturns& target, const Isometry3& T_target_source,
                                const ReturnsRefineParams& returns, const RefinementParams& solver,
                                const SweepMotionParams& params = {}, double max_incidence_deg = 80.0);

}  // namespace gasp
