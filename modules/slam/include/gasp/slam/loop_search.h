#pragma once
/// \file loop_search.h One new keyframe's loop search, the one both DepthSlam and the graph-SLAM
/// edge decider (CGaspLoopClosureERD) run: every loop candidate near the current estimate
/// (loopCandidates) registered to the keyframe, gated against the odometry's prediction and
/// taken when it agrees; then, when the graph has several pieces, relocalisation candidates of
/// the other pieces (relocalisationCandidates) registered and offered as votes, the pieces joined
/// when enough votes agree (relocalisation.h). The owner keeps the graph; it says how to reach
/// the views and where taken constraints go.
#include <cstddef>
#include <functional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "gasp/association/place_descriptor.h"
#include "gasp/slam/loop_closure.h"
#include "gasp/slam/relocalisation.h"

namespace gasp {

struct LoopRegistration;

/// A failure of the job rather than of one input -- a registration journal that cannot be written,
/// another process of the job that failed (registration_log.h, gasp::mpi) -- raised through a
/// loop search. Not a gasp::Error, so that a program reading several sessions ends the job
/// instead of recording it as the session's error and going on without the registrations.
class JobError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// How a registration that threw where it ran is returned (registerCandidate()): no estimate, its
/// reason starting with this and naming where and why. The job goes on without it; a journal does
/// not keep it, so a resumed job tries it again.
inline constexpr const char* kRegistrationFailed = "the registration failed";

/// Registers one phase's candidates to keyframe k, in the candidates' order: registerCandidates()
/// (below), or anything that returns the same registrations -- a log of them from an earlier run
/// (registration_log.h), another process.
using CandidateRegistrar = std::function<std::vector<LoopRegistration>(
    std::size_t k, const DepthView& view_k, const std::vector<std::pair<std::size_t, const DepthView*>>& candidates,
    bool relocalisation, const PairParams& pair, const LoopClosureParams& loop)>;

/// The owner's graph, as the search sees it.
struct LoopSearchGraph {
  std::size_t node_count = 0;
  std::vector<std::size_t> keyframes;     ///< nodes with a view, ascending (the new keyframe last)
  std::vector<Isometry3> T_world_camera;  ///< the current estimate of every node's camera
  std::vector<PoseConstraint> tree;       ///< the odometry's constraints (its prediction)
  std::function<const DepthView&(std::size_t node)> view;
  std::function<std::vector<PoseConstraint>()> links;  ///< every constraint now: the tree and the closures taken
  /// The keyframes before `k` whose place descriptors are nearest to k's, nearest first
  /// (PlaceIndex); needed when LoopClosureParams::search uses retrieval (empty: the owner has no
  /// descriptors, and such a search is an error).
  std::function<std::vector<std::size_t>(std::size_t k)> retrieve;
  /// A constraint taken: its attempt's index and its group (0: a loop closure; else the vote
  /// group of a relocalisation, whose votes entered together).
  std::function<void(const PoseConstraint& c, std::size_t attempt, std::size_t group)> insert;
  /// Called before agreeing votes join two pieces (`newest`: the vote that completed them,
  /// `roots`: the pieces before the join); returns "" to join, or the reason none of the votes is
  /// used (the votes are then let go).
  std::function<std::string(const PoseConstraint& newest, const RelocalisationVotes::Decision& d,
                            const std::vector<std::size_t>& roots)>
      before_join;
  /// Who registers the candidates (empty: registerCandidates()).
  CandidateRegistrar register_candidates;
};

/// A keyframe's place descriptor (place_descriptor.h): its view's patches through the pair's
/// feature sets. Empty (no features) for a view without patches.
PlaceDescriptor describeKeyframe(const DepthView& view, const PairParams& pair);
/// LoopSearchGraph::retrieve for an owner that keeps its keyframes' descriptors in `places`: the
/// keyframes before `k`, nearest to k's descriptor first; none when k has no descriptor.
std::vector<std::size_t> retrieveEarlier(const PlaceIndex& places, std::size_t k);

/// The search for keyframe `k` (a node of `graph`). Appends every registration to `attempts`;
/// `votes` and `vote_groups` carry the relocalisations waiting for agreement and the groups taken
/// so far across keyframes. Returns whether any constraint was taken. It is the two phases below,
/// one after the other, each registered where it is planned.
bool searchLoops(std::size_t k, const LoopSearchGraph& graph, const PairParams& pair, const LoopClosureParams& loop,
                 std::vector<LoopClosureAttempt>& attempts, RelocalisationVotes& votes, std::size_t& vote_groups);

/// The search in parts, for an owner that registers on another thread (DepthSlam with
/// LoopClosureParams::background): per phase, the candidates are chosen on the graph as it is,
/// registered by registerCandidates() (the views and parameters only: safe on any thread while
/// the views stay put), and the registrations taken into the graph. Phase 1 (near loops) must be
/// taken before phase 2 (relocalisation) is planned: a near loop may join the pieces phase 2
/// would otherwise try.
struct LoopRegistration {
  LoopClosureAttempt attempt;  ///< its reason set when there is no estimate or too few inliers
  PoseConstraint constraint;
};

/// Phase 1's candidates: earlier keyframes near `k` (loopCandidates()) and/or those whose place
/// descriptors are nearest (LoopClosureParams::search; at most retrieval_candidates, in k's piece,
/// at least min_keyframe_gap keyframes back, none twice); `k` must be the last of
/// graph.keyframes (gasp::Error otherwise, as for phase 2, and for a retrieval without
/// graph.retrieve).
std::vector<std::size_t> nearLoopCandidates(std::size_t k, const LoopSearchGraph& graph, const LoopClosureParams& loop);
/// Phase 2's: the latest keyframes of the other pieces (relocalisationCandidates()) and/or the
/// other pieces' keyframes with the nearest place descriptors (LoopClosureParams::search; at most
/// relocalisation_candidates of each kind, none twice); none when relocalisation is off.
std::vector<std::size_t> relocalisationCandidatesOf(std::size_t k, const LoopSearchGraph& graph,
                                                    const LoopClosureParams& loop);
/// Keyframe `k`'s view (`view_k`) registered to a candidate's (registerLoopClosure()). What it
/// throws comes back as a failed registration: its reason kRegistrationFailed, `where` (e.g. " on
/// rank 2") and the error.
LoopRegistration registerCandidate(std::size_t k, const DepthView& view_k, std::size_t candidate,
                                   const DepthView& view_candidate, bool relocalisation, const PairParams& pair,
                                   const LoopClosureParams& loop, const std::string& where = "");
/// Keyframe `k`'s view (`view_k`) registered to each candidate's (registerCandidate()).
std::vector<LoopRegistration> registerCandidates(std::size_t k, const DepthView& view_k,
                                                 const std::vector<std::pair<std::size_t, const DepthView*>>& candidates,
                                                 bool relocalisation, const PairParams& pair,
                                                 const LoopClosureParams& loop);
/// Phase 1 taken: each registration gated against the odometry and inserted when it agrees.
bool takeNearLoops(std::size_t k, const LoopSearchGraph& graph, std::vector<LoopRegistration> registered,
                   const LoopClosureParams& loop, std::vector<LoopClosureAttempt>& attempts);
/// Phase 2 taken: each registration offered as a vote, the pieces joined when enough agree; a
/// candidate whose piece an earlier vote of this phase joined to k's is left out (as if never tried).
bool takeRelocalisations(std::size_t k, const LoopSearchGraph& graph, std::vector<LoopRegistration> registered,
                         std::vector<LoopClosureAttempt>& attempts, RelocalisationVotes& votes,
                         std::size_t& vote_groups);

}  // namespace gasp
