#pragma once
/// \file relocalisation.h Joining two pieces of a pose graph only when several relocalisations
/// agree: a single registration with no pose prior may be wrong, and as the only edge between
/// two pieces the optimised graph could never contradict it.
#include <cstddef>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "gasp/odometry/pose_constraint.h"
#include "gasp/slam/pose_graph.h"
#include "gasp/slam/slam_params.h"

namespace gasp {

/// The relative pose `from` -> `to` predicted through relocalisation `h`: the path inside the
/// piece of `from` to one end of h, h (inverted when its ends lie the other way round), the path
/// inside the piece of `to` from h's other end; the paths are composed along `tree` (the
/// odometry's constraints, composeAlongTree()), the covariances carried to frame `from` to first
/// order. Empty when `from` and `to` are not in the pieces h links, or a path is missing.
std::optional<RelativePoseEstimate> predictThroughRelocalisation(const std::vector<PoseConstraint>& tree,
                                                                 std::size_t frame_count, const PoseConstraint& h,
                                                                 std::size_t from, std::size_t to);

/// Successful relocalisation registrations (constraints between two pieces) wait here until
/// `LoopClosureParams::relocalisation_agreeing` of them link the same two pieces consistently:
/// each waiting one predicts the new one's relative pose (predictThroughRelocalisation()), and
/// agrees when xi^T (S_pred + S_meas)^-1 xi <= gate_chi2. The votes that join agree with each
/// other as well (each pair: one predicts the other within the gate), not only with the new one.
class RelocalisationVotes {
 public:
  /// A relocalisation and the index of its attempt (the caller's bookkeeping).
  struct Vote {
    PoseConstraint constraint;
    std::size_t attempt = 0;
  };
  /// What offer() decided.
  struct Decision {
    bool join = false;        ///< insert `votes` (the agreeing waiting ones, then the new one)
    std::vector<Vote> votes;  ///< when join
    /// Least chi-square of the new relocalisation against a waiting one linking the same pieces
    /// (NaN when none could predict it).
    double chi2 = std::numeric_limits<double>::quiet_NaN();
    std::string reason;  ///< why it waits (empty when join)
  };

  /// At most this many waiting votes (the best by their chi-square against the new one) enter
  /// the search for the largest agreeing set, which bounds its exponential worst case.
  static constexpr std::size_t kMaxCandidates = LoopClosureParams::kMaxRelocalisationAgreeing - 1;

  explicit RelocalisationVotes(const LoopClosureParams& params) : params_(params) {}

  /// Offers a successful relocalisation `c` (between two pieces under `roots`, pieceRoots()).
  /// With relocalisation_agreeing - 1 waiting ones agreeing with it and among themselves,
  /// returns join with them and removes them from the waiting list; otherwise `c` waits. The
  /// ones that join are the largest set of waiting ones that agree with `c` and pairwise among
  /// themselves (a maximum clique, searched exactly over the kMaxCandidates that agree best with
  /// `c`); of equally large sets, the one of the best-agreeing votes.
  Decision offer(const PoseConstraint& c, std::size_t attempt, const std::vector<PoseConstraint>& tree,
                 std::size_t frame_count, const std::vector<std::size_t>& roots);

  /// Removes the waiting relocalisations whose two ends are now in one piece (joined by other
  /// votes or loop closures); returns them.
  std::vector<Vote> removeJoined(const std::vector<std::size_t>& roots);

  const std::vector<Vote>& waiting() const { return waiting_; }

 private:
  LoopClosureParams params_;
  std::vector<Vote> waiting_;
};

}  // namespace gasp
