#include "gasp/odometry/scene_change.h"

#include <cmath>
#include <cstdio>
#include <tuple>
#include <utility>

#include "gasp/core/error.h"

namespace gasp {

namespace {

void requireRatio(double v, const char* name) {
  if (!(v >= 0.0 && v <= 1.0)) throw Error(std::string("odometry: scene_change.") + name + " must be in [0, 1]");
}

void requireNonNegative(double v, const char* name) {
  if (!(v >= 0.0) || !std::isfinite(v))
    throw Error(std::string("odometry: scene_change.") + name + " must be finite and >= 0");
}

}  // namespace

void validate(const SceneChangeParams& p) {
  requireRatio(p.max_violation_ratio, "max_violation_ratio");
  requireRatio(p.max_two_way_violation_ratio, "max_two_way_violation_ratio");
  requireRatio(p.max_occluded_ratio, "max_occluded_ratio");
  requirePositive(p.gate_m, "odometry: scene_change.gate_m");
  requirePositive(p.gate_deg, "odometry: scene_change.gate_deg");
  requireNonNegative(p.max_accel_mps2, "max_accel_mps2");
  requireNonNegative(p.max_angular_accel_radps2, "max_angular_accel_radps2");
  requirePositive(p.max_gate_m, "odometry: scene_change.max_gate_m");
  requirePositive(p.max_gate_deg, "odometry: scene_change.max_gate_deg");
}

PairParams sceneChangePairParams(const PairParams& pair, const SceneChangeParams& p) {
  PairParams out = pair;
  out.certify.visibility.max_violation_ratio = p.max_violation_ratio;
  out.certify.visibility.max_two_way_violation_ratio = p.max_two_way_violation_ratio;
  out.certify.visibility.max_occluded_ratio = p.max_occluded_ratio;
  out.certify.fallback_max_violation_ratio = p.max_violation_ratio;  // also the finer-scale retry's limit
  return out;
}

std::pair<double, double> gateAt(double dt, const SceneChangeParams& p) {
  const double half_dt2 = 0.5 * dt * dt;
  return {p.gate_m + p.max_accel_mps2 * half_dt2, p.gate_deg + p.max_angular_accel_radps2 * half_dt2 * 180.0 / M_PI};
}

std::string predictionTooWide(double dt, const SceneChangeParams& p) {
  const auto [gate_m, gate_deg] = gateAt(dt, p);
  if (gate_m <= p.max_gate_m && gate_deg <= p.max_gate_deg) return {};
  char buf[200];
  std::snprintf(buf, sizeof buf, "not tried: over %.3f s the prediction's gate, %.3f m / %.2f deg, is wider than %.3f m / %.2f deg",
                dt, gate_m, gate_deg, p.max_gate_m, p.max_gate_deg);
  return buf;
}

PredictionGate predictionGate(const Isometry3& T_ref_estimated, const Isometry3& T_ref_predicted, double dt,
                              const SceneChangeParams& p) {
  PredictionGate g;
  std::tie(g.gate_m, g.gate_deg) = gateAt(dt, p);
  g.off_m = (T_ref_estimated.translation() - T_ref_predicted.translation()).norm();
  g.off_deg = rotationAngle(T_ref_predicted.inverse() * T_ref_estimated) * 180.0 / M_PI;
  return g;
}

std::string PredictionGate::describe() const {
  char buf[200];
  std::snprintf(buf, sizeof buf, "%.3f m / %.2f deg from the constant-velocity prediction (gate %.3f m / %.2f deg)",
                off_m, off_deg, gate_m, gate_deg);
  return buf;
}

}  // namespace gasp
