#include "gasp/slam/loop_closure.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "gasp/core/error.h"

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

}  // namespace gasp
