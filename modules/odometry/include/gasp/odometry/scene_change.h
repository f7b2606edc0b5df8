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
#include <utility>

#include "gasp/core/pose.h"
#include "gasp/pipeline/pair_registration.h"

namespace gasp {

struct SceneChangeParams {
  bool enabled = true;  ///< false: a refused frame is predicted, as before
  /// Visibility limits of the scene-change attempt (the pair's defaults: 0.15, 0.05, 0.5): loose
  /// enough for a moved object, an occluder popping in or a person stepping aside, and a larger
  /// change is refused (docs/odometry.md "Scenes that change").
  double max_violation_ratio = 0.6;          ///< in [0, 1]; also the one-way fallback's and the retry's limit
  double max_two_way_violation_ratio = 0.3;  ///< in [0, 1]
  double max_occluded_ratio = 0.8;           ///< in [0, 1]
  /// The prediction gate: GASP's pose must lie within gate_m + max_accel_mps2 dt^2 / 2 of the
  /// constant-velocity prediction, and its rotation within gate_deg + max_angular_accel_radps2
  /// dt^2 / 2 (dt: time since the previous frame). The floors cover GASP's own error and the
  /// prediction's at 30 Hz; the accelerations bound a hand-held camera's change of velocity
  /// between frames (at 5 Hz the gate is 6 cm and 7.7 deg).
  double gate_m = 0.02;                     ///< [m], > 0
  double gate_deg = 2.0;                    ///< [deg], > 0
  double max_accel_mps2 = 2.0;              ///< [m/s^2], >= 0
  double max_angular_accel_radps2 = 5.0;    ///< [rad/s^2], >= 0
  /// The attempt is made only while the gate is at most this wide: a prediction over a long time
  /// vouches for nothing (over seconds the gate above grows to metres). With the defaults:
  /// frames at most 0.236 s apart (about 4.2 Hz and faster). The limit stays well below how far
  /// the wrong poses the visibility check declines lie from the truth.
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

/// The gate dt seconds after the reference: [m], [deg].
std::pair<double, double> gateAt(double dt, const SceneChangeParams& params);

PredictionGate predictionGate(const Isometry3& T_ref_estimated, const Isometry3& T_ref_predicted, double dt,
                              const SceneChangeParams& params);

/// Empty when a prediction dt seconds ahead is narrow enough to vouch for a pose (its gate within
/// max_gate_m and max_gate_deg), else why not.
std::string predictionTooWide(double dt, const SceneChangeParams& params);

}  // namespace gasp
