#include "gasp/slam/loop_closure.h"

#include <Eigen/Cholesky>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <utility>

#include "gasp/core/error.h"
#include "gasp/core/format.h"
#include "gasp/core/pose_perturbation.h"
#include "gasp/core/stopwatch.h"

namespace gasp {

std::vector<std::size_t> loopCandidates(const std::vector<std::size_t>& keyframes,
                                        const std::vector<Isometry3>& T_world_frame,
                                        const std::vector<std::size_t>& piece_root, const LoopClosureParams& p) {
  if (keyframes.empty()) return {};
  for (const std::size_t k : keyframes)
    if (k >= T_world_frame.size() || k >= piece_root.size())
      throw Error("loop closure: keyframe " + std::to_string(k) + " has no pose");
  const std::size_t current = keyframes.back(), n = keyframes.size();
  const Isometry3& T_c = T_world_frame[current];
  const double cos_max = std::cos(p.max_axis_angle_deg * M_PI / 180.0);
  std::vector<std::pair<double, std::size_t>> near;  // (distance, position in keyframes)
  for (std::size_t pos = 0; pos + p.min_keyframe_gap < n; ++pos) {
    const std::size_t k = keyframes[pos];
    if (piece_root[k] != piece_root[current]) continue;
    const Isometry3& T_k = T_world_frame[k];
    const double d = (T_k.translation() - T_c.translation()).norm();
    const double cos_axes = T_k.linear().col(2).dot(T_c.linear().col(2));
    if (d <= p.search_radius_m && cos_axes >= cos_max) near.emplace_back(d, pos);
  }
  std::sort(near.begin(), near.end());
  std::vector<std::size_t> chosen_pos, out;
  for (const auto& [d, pos] : near) {
    if (out.size() >= p.max_candidates) break;
    const bool apart = std::all_of(chosen_pos.begin(), chosen_pos.end(), [&, pos = pos](std::size_t q) {
      return (pos > q ? pos - q : q - pos) >= p.min_keyframe_gap;
    });
    if (!apart) continue;
    chosen_pos.push_back(pos);
    out.push_back(keyframes[pos]);
  }
  return out;
}

std::vector<std::size_t> relocalisationCandidates(const std::vector<std::size_t>& keyframes,
                                                  const std::vector<std::size_t>& piece_root,
                                                  const LoopClosureParams& p) {
  std::vector<std::size_t> out;
  if (keyframes.empty()) return out;
  const std::size_t current = keyframes.back();
  if (current >= piece_root.size()) throw Error("loop closure: keyframe " + std::to_string(current) + " has no pose");
  for (const std::size_t k : keyframes)
    if (k >= piece_root.size()) throw Error("loop closure: keyframe " + std::to_string(k) + " has no pose");
  // First the latest keyframe of each other piece (the latest piece first), so that a recent
  // piece cannot take every slot; then the next latest of them, and so on.
  std::vector<std::size_t> pieces_seen;
  for (std::size_t round = 0; out.size() < p.relocalisation_candidates; ++round) {
    bool any = false;
    std::vector<std::size_t> taken_in_piece;  // per piece in pieces_seen: keyframes taken so far
    for (std::size_t pos = keyframes.size() - 1; pos-- > 0 && out.size() < p.relocalisation_candidates;) {
      const std::size_t k = keyframes[pos], piece = piece_root[k];
      if (piece == piece_root[current]) continue;
      const auto it = std::find(pieces_seen.begin(), pieces_seen.end(), piece);
      const std::size_t slot = static_cast<std::size_t>(it - pieces_seen.begin());
      if (it == pieces_seen.end()) pieces_seen.push_back(piece);
      if (taken_in_piece.size() < pieces_seen.size()) taken_in_piece.resize(pieces_seen.size(), 0);
      // In round r, the (r+1)-th latest keyframe of each piece.
      if (taken_in_piece[slot]++ != round) continue;
      out.push_back(k);
      any = true;
    }
    if (!any) break;
  }
  return out;
}

LoopClosureAttempt registerLoopClosure(const DepthView& from_view, const DepthView& to_view, std::size_t from,
                                       std::size_t to, bool relocalisation, const PairParams& pair,
                                       const LoopClosureParams& params, PoseConstraint& c) {
  LoopClosureAttempt a;
  a.from = from;
  a.to = to;
  a.relocalisation = relocalisation;
  const auto t0 = std::chrono::steady_clock::now();
  const PairResult r = registerViews(to_view, from_view, pair);
  a.registration_ms = msSince(t0);
  a.inliers = r.pose.success ? r.pose.num_inliers : 0;
  const int min_inliers = relocalisation ? params.relocalisation_min_inliers : params.min_inliers;
  if (!r.pose.success) {
    a.reason = "no estimate: " + r.pose.reason;
  } else if (r.pose.num_inliers < min_inliers) {
    a.reason = formatted("%d inliers, fewer than %d", r.pose.num_inliers, min_inliers);
  }
  c = PoseConstraint{};
  c.from = from;
  c.to = to;
  c.T_from_to = r.pose.T_target_source;
  c.information = r.edge_information;
  c.inliers = a.inliers;
  c.loop_closure = true;
  return a;
}

void gateLoopClosure(const PoseConstraint& c, const std::optional<RelativePoseEstimate>& prediction,
                     const LoopClosureParams& params, LoopClosureAttempt& a) {
  if (prediction) {
    // The prediction's own covariance describes it (not that of optimised poses).
    const Vector6 xi = leftPerturbation(c.T_from_to, prediction->T_a_b);
    const Matrix6 S = prediction->covariance + c.information.ldlt().solve(Matrix6::Identity());
    a.gate_chi2 = xi.dot(S.ldlt().solve(xi));
    if (!(a.gate_chi2 <= params.gate_chi2))
      a.reason = formatted("disagrees with the odometry: chi-square %.1f > %.2f", a.gate_chi2, params.gate_chi2);
  } else if (a.inliers < params.relocalisation_min_inliers) {
    // Joined only through other loop closures: no odometry path to check it against.
    a.reason = formatted("no odometry path to check against, and %d inliers, fewer than %d", a.inliers,
                         params.relocalisation_min_inliers);
  }
}

}  // namespace gasp
