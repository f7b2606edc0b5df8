#pragma once
/// \file scene_change.h Tracking through a scene that changes (an object moved, a person walked
/// in) with the motion prediction as the witness.
///
/// The visibility check (visibility_check.h) assumes a static world: a pose under which one
/// view's surfaces stand in space the other saw as empty is refused. Between two frames of a
/// sequence a moved object does exactly that, so the frame is lost and the pose graph breaks
/// in two (docs/odometry.md, "Scenes that change"). Pair registration has nothing else to go
/// on; the odometry has the camera's last velocity. When both strict attempts fail and the
/// visibility check refused the pose of one of them (PairResult::visibility_refused), the frame
/// is registered to the previous frame once more with the looser limits below, and the pose is
/// taken only when it lies within a gate of the constant-velocity prediction: the prediction,
/// not the free-space test, then vouches that the alignment is not a look-alike one (look-alike
/// poses are a quarter or half turn, or tens of centimetres, away from the truth;
/// docs/pipeline.md "Violations seen from both views").
#include <string>

#include "gasp/core/pose.h"
#include "gasp/pipeline/pair_registration.h"

namespace gasp {

struct SceneChangeParams {
  bool enabled = true;  ///< false: a refused frame is predicted, as before
  /// Visibility limits of the scene-change attempt (the pair's defaults: 0.15, 0.05, 0.5). The
  /// frames taken on the simulator's moved objects had 7.8-15.1 % in one direction and up to
  /// 14.9 % in the other (the chair pushed 0.6 m: 15.1 % / 14.9 %), the occluder popping in 42 %
  /// in one direction and the person stepping aside 56.7 %, near the 60 % (docs/odometry.md
  /// "Scenes that change"): a larger change is refused.
  double max_violation_ratio = 0.6;          ///< in [0, 1]; also the one-way fallback's and the retry's limit
  double max_two_way_violation_ratio = 0.3;  ///< in [0, 1]
  double max_occluded_ratio = 0.8;           ///< in [0, 1]
  /// The prediction gate: GASP's pose must lie within gate_m + max_accel_mps2 dt^2 / 2 of the
  /// constant-velocity prediction, and its rotation within gate_deg + max_angular_accel_radps2
  /// dt^2 / 2 (dt: time since the previous frame). The floors cover GASP's own error (1-2 cm,
  /// 0.5-1.5 deg on fr1_xyz pairs) and the prediction's at 30 Hz (fr1_xyz against its
  /// reference: 95 % within 2 mm and 0.84 deg, at most 5 mm and 1.6 deg); the accelerations
  /// bound a hand-held camera's change of velocity between frames (at 5 Hz the gate is 6 cm
  /// and 7.7 deg).
  double gate_m = 0.02;                     ///< [m], > 0
  double gate_deg = 2.0;                    ///< [deg], > 0
  double max_accel_mps2 = 2.0;              ///< [m/s^2], >= 0
  double max_angular_accel_radps2 = 5.0;    ///< [rad/s^2], >= 0
  /// The attempt is made only while the gate is at most this wide: a prediction over a long time
  /// vouches for nothing (at dt = 2.7 s, fr3_cabinet_kf's keyframes four apart, the gate above
  /// is 7.3 m wide). With the defaults: frames at most 0.236 s apart (about 4.2 Hz and faster).
  /// The wrong poses the visibility check declines are 0.3-1.6 m or 5-180 deg from the truth.
  double max_gate_m = 0.10;    ///< [m], > 0
  double max_gate_deg = 10.0;  ///< [deg], > 0
};

/// Throws gasp::Error naming the first invalid field.
void validate(const SceneChangeParams& params);

/// `pair` with the scene-change attempt's visibility limits (the one-way fallback's and the
/// finer-scale retry's limit raised to max_violation_ratio as well); everything else unchanged.
PairParams sceneChangePairParams(const PairParams& pair, const SceneChangeParams& params);

/// How far an estimated pose of a frame (in its reference's frame) lies from the predicted one,
/// dt seconds after the reference, and the gate it must lie within.
struct PredictionGate {
  double off_m = 0.0, off_deg = 0.0;    ///< distance of the positions, angle between the rotations
  double gate_m = 0.0, gate_deg = 0.0;  ///< SceneChangeParams' gate at this dt
  bool within() const { return off_m <= gate_m && off_deg <= gate_deg; }  ///< false for NaN
  std::string describe() const;  ///< "0.004 m / 0.10 deg from the constant-velocity prediction (gate ...)"
};

PredictionGate predictionGate(const Isometry3& T_ref_estimated, const Isometry3& T_ref_predicted, double dt,
                              const SceneChangeParams& params);

/// Empty when a prediction dt seconds ahead is narrow enough to vouch for a pose (its gate within
/// max_gate_m and max_gate_deg), else why not.
std::string predictionTooWide(double dt, const SceneChangeParams& params);

}  // namespace gasp
