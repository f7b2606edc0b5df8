#include "gasp/slam/loop_search.h"

#include <algorithm>
#include <string>
#include <utility>

#include "gasp/association/feature_sets.h"
#include "gasp/association/patch_geometry.h"
#include "gasp/core/error.h"
#include "gasp/slam/pose_graph.h"

namespace gasp {

namespace {

/// The candidates with their views, as the graph gives them.
std::vector<std::pair<std::size_t, const DepthView*>> withViews(const std::vector<std::size_t>& candidates,
                                                                const LoopSearchGraph& g) {
  std::vector<std::pair<std::size_t, const DepthView*>> out;
  out.reserve(candidates.size());
  for (const std::size_t c : candidates) out.emplace_back(c, &g.view(c));
  return out;
}

/// The candidates are chosen for the graph's last keyframe: it must be k.
void requireLast(std::size_t k, const LoopSearchGraph& g) {
  if (g.keyframes.empty() || g.keyframes.back() != k)
    throw Error("loop search: keyframe " + std::to_string(k) + " is not the last keyframe of the graph searched");
}

/// Appends to `out` up to `count` keyframes before k, nearest to it by place descriptor first,
/// that `keep` accepts and `out` does not hold yet.
template <class Keep>
void appendRetrieved(std::size_t k, const LoopSearchGraph& g, std::size_t count, std::vector<std::size_t>& out,
                     Keep&& keep) {
  if (!g.retrieve) throw Error("loop search: retrieval needs the keyframes' place descriptors, and this graph has none");
  std::size_t taken = 0;
  for (const std::size_t c : g.retrieve(k)) {
    if (taken >= count) break;
    if (!keep(c) || std::find(out.begin(), out.end(), c) != out.end()) continue;
    out.push_back(c);
    ++taken;
  }
}

}  // namespace

PlaceDescriptor describeKeyframe(const DepthView& view, const PairParams& pair) {
  return describePlace(computeFeatureSets(toPatchGeometry(view.segmentation.patches), pair.associate.feature_sets));
}

std::vector<std::size_t> retrieveEarlier(const PlaceIndex& places, std::size_t k) {
  std::vector<std::size_t> out;
  const PlaceDescriptor* d = places.find(k);
  if (!d) return out;  // no descriptor (no features): nothing to retrieve with
  for (const auto& nearest : places.query(*d, places.size(), [k](std::size_t id) { return id >= k; }))
    out.push_back(nearest.first);
  return out;
}

std::vector<std::size_t> nearLoopCandidates(std::size_t k, const LoopSearchGraph& g, const LoopClosureParams& loop) {
  requireLast(k, g);
  const std::vector<std::size_t> roots = pieceRoots(g.node_count, g.links());
  std::vector<std::size_t> out;
  if (loop.search != LoopSearch::kRetrieval) out = loopCandidates(g.keyframes, g.T_world_camera, roots, loop);
  if (loop.search == LoopSearch::kRadius) return out;
  // Keyframes at least min_keyframe_gap back (before position n - gap in g.keyframes), in k's piece.
  const std::size_t n = g.keyframes.size();
  appendRetrieved(k, g, loop.retrieval_candidates, out, [&](std::size_t c) {
    const auto pos = std::find(g.keyframes.begin(), g.keyframes.end(), c);
    return pos != g.keyframes.end() && static_cast<std::size_t>(pos - g.keyframes.begin()) + loop.min_keyframe_gap < n &&
           roots[c] == roots[k];
  });
  return out;
}

std::vector<std::size_t> relocalisationCandidatesOf(std::size_t k, const LoopSearchGraph& g,
                                                    const LoopClosureParams& loop) {
  requireLast(k, g);
  if (loop.relocalisation_candidates == 0) return {};
  const std::vector<std::size_t> roots = pieceRoots(g.node_count, g.links());
  std::vector<std::size_t> out;
  if (loop.search != LoopSearch::kRetrieval) out = relocalisationCandidates(g.keyframes, roots, loop);
  if (loop.search == LoopSearch::kRadius) return out;
  // The nearest descriptors of the other pieces, as many again as the latest keyframes' rule takes.
  appendRetrieved(k, g, loop.relocalisation_candidates, out, [&](std::size_t c) { return roots[c] != roots[k]; });
  return out;
}

std::vector<LoopRegistration> registerCandidates(std::size_t k, const DepthView& view_k,
                                                 const std::vector<std::pair<std::size_t, const DepthView*>>& candidates,
                                                 bool relocalisation, const PairParams& pair,
                                                 const LoopClosureParams& loop) {
  std::vector<LoopRegistration> out;
  out.reserve(candidates.size());
  for (const auto& [candidate, view] : candidates)
    out.push_back(registerCandidate(k, view_k, candidate, *view, relocalisation, pair, loop));
  return out;
}

LoopRegistration registerCandidate(std::size_t k, const DepthView& view_k, std::size_t candidate,
                                   const DepthView& view_candidate, bool relocalisation, const PairParams& pair,
                                   const LoopClosureParams& loop, const std::string& where) {
  LoopRegistration r;
  try {
    r.attempt = registerLoopClosure(view_candidate, view_k, candidate, k, relocalisation, pair, loop, r.constraint);
  } catch (const std::exception& e) {  // reported, and the job goes on
    r = LoopRegistration{};
    r.attempt.from = r.constraint.from = candidate;
    r.attempt.to = r.constraint.to = k;
    r.attempt.relocalisation = relocalisation;
    r.constraint.loop_closure = true;
    r.attempt.reason = std::string(kRegistrationFailed) + where + ": " + e.what();
  }
  return r;
}

bool takeNearLoops(std::size_t k, const LoopSearchGraph& g, std::vector<LoopRegistration> registered,
                   const LoopClosureParams& loop, std::vector<LoopClosureAttempt>& attempts) {
  bool taken = false;
  for (LoopRegistration& r : registered) {
    LoopClosureAttempt& a = r.attempt;
    // Agreement with the odometry between the two keyframes, within both uncertainties.
    if (a.reason.empty()) gateLoopClosure(r.constraint, composeAlongTree(g.tree, g.node_count, a.from, k), loop, a);
    a.accepted = a.reason.empty();
    attempts.push_back(std::move(a));
    if (!attempts.back().accepted) continue;
    g.insert(r.constraint, attempts.size() - 1, 0);
    taken = true;
  }
  return taken;
}

bool takeRelocalisations(std::size_t k, const LoopSearchGraph& g, std::vector<LoopRegistration> registered,
                         std::vector<LoopClosureAttempt>& attempts, RelocalisationVotes& votes,
                         std::size_t& vote_groups) {
  bool taken = false;
  std::vector<std::size_t> roots = pieceRoots(g.node_count, g.links());
  for (LoopRegistration& r : registered) {
    if (roots[r.attempt.from] == roots[k]) continue;  // joined by an earlier candidate
    const PoseConstraint& c = r.constraint;
    attempts.push_back(std::move(r.attempt));
    if (!attempts.back().reason.empty()) continue;
    // A vote: the pieces are joined when enough votes agree (relocalisation.h).
    const RelocalisationVotes::Decision d = votes.offer(c, attempts.size() - 1, g.tree, g.node_count, roots);
    attempts.back().gate_chi2 = d.chi2;
    if (!d.join) {
      attempts.back().reason = d.reason;
      continue;
    }
    // The votes enter the graph together or not at all: fewer would be an unchecked join.
    if (const std::string refused = g.before_join ? g.before_join(c, d, roots) : std::string(); !refused.empty()) {
      for (const RelocalisationVotes::Vote& v : d.votes) attempts[v.attempt].reason = refused;
      continue;
    }
    ++vote_groups;
    for (const RelocalisationVotes::Vote& v : d.votes) {
      attempts[v.attempt].accepted = true;
      attempts[v.attempt].reason.clear();
      g.insert(v.constraint, v.attempt, vote_groups);
    }
    taken = true;
    roots = pieceRoots(g.node_count, g.links());
    for (const RelocalisationVotes::Vote& v : votes.removeJoined(roots))
      attempts[v.attempt].reason = "not used: its pieces were joined by other votes";
  }
  return taken;
}

bool searchLoops(std::size_t k, const LoopSearchGraph& g, const PairParams& pair, const LoopClosureParams& loop,
                 std::vector<LoopClosureAttempt>& attempts, RelocalisationVotes& votes, std::size_t& vote_groups) {
  const DepthView& view_k = g.view(k);
  // One phase's candidates registered by the graph's registrar (none to register: none asked).
  const auto registered = [&](const std::vector<std::size_t>& candidates, bool relocalisation) {
    if (candidates.empty()) return std::vector<LoopRegistration>{};
    if (g.register_candidates) return g.register_candidates(k, view_k, withViews(candidates, g), relocalisation, pair, loop);
    return registerCandidates(k, view_k, withViews(candidates, g), relocalisation, pair, loop);
  };
  bool taken = takeNearLoops(k, g, registered(nearLoopCandidates(k, g, loop), false), loop, attempts);
  const std::vector<std::size_t> relocalisation = relocalisationCandidatesOf(k, g, loop);
  if (relocalisation.empty()) return taken;
  taken = takeRelocalisations(k, g, registered(relocalisation, true), attempts, votes, vote_groups) || taken;
  return taken;
}

}  // namespace gasp
