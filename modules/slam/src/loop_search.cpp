#include "gasp/slam/loop_search.h"

#include <utility>

#include "gasp/slam/pose_graph.h"

namespace gasp {

namespace {

/// The loop candidates near the estimate: registered, gated against the odometry, taken.
bool closeNearLoops(std::size_t k, const LoopSearchGraph& g, const PairParams& pair, const LoopClosureParams& loop,
                    std::vector<LoopClosureAttempt>& attempts) {
  bool taken = false;
  const std::vector<std::size_t> roots = pieceRoots(g.node_count, g.links());
  for (const std::size_t cand : loopCandidates(g.keyframes, g.T_world_camera, roots, loop)) {
    PoseConstraint c;
    LoopClosureAttempt a = registerLoopClosure(g.view(cand), g.view(k), cand, k, false, pair, loop, c);
    // Agreement with the odometry between the two keyframes, within both uncertainties.
    if (a.reason.empty()) gateLoopClosure(c, composeAlongTree(g.tree, g.node_count, cand, k), loop, a);
    a.accepted = a.reason.empty();
    attempts.push_back(std::move(a));
    if (!attempts.back().accepted) continue;
    g.insert(c, attempts.size() - 1, 0);
    taken = true;
  }
  return taken;
}

}  // namespace

bool searchLoops(std::size_t k, const LoopSearchGraph& g, const PairParams& pair, const LoopClosureParams& loop,
                 std::vector<LoopClosureAttempt>& attempts, RelocalisationVotes& votes, std::size_t& vote_groups) {
  bool taken = closeNearLoops(k, g, pair, loop, attempts);
  if (loop.relocalisation_candidates == 0) return taken;
  std::vector<std::size_t> roots = pieceRoots(g.node_count, g.links());
  for (const std::size_t cand : relocalisationCandidates(g.keyframes, roots, loop)) {
    if (roots[cand] == roots[k]) continue;  // joined by an earlier candidate
    PoseConstraint c;
    attempts.push_back(registerLoopClosure(g.view(cand), g.view(k), cand, k, true, pair, loop, c));
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

}  // namespace gasp
