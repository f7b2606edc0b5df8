#pragma once
/// \file depth_slam.h GASP's depth SLAM: the odometry (odometry.h), loop closures between
/// keyframes, and the pose graph of both optimised (pose_graph_optimizer.h).
///
/// Each new keyframe is registered, with the whole pair front-end and no initial guess, to up to
/// `max_candidates` earlier keyframes near it at the current estimate (loop_closure.h). A
/// registration is taken as a loop closure when it agrees with the odometry within the
/// uncertainty of the odometry constraints between the two keyframes (a chi-square gate); the
/// graph is then optimised, and a closure that the optimised graph contradicts is dropped. When
/// the odometry lost track and the graph fell into pieces, new keyframes are also registered to
/// the latest keyframes of the other pieces (relocalisation), which joins them.
///
/// With LoopClosureParams::background (the default) a keyframe's registrations run on a thread
/// of their own while the next frames are tracked; what they give is taken into the graph, and
/// the graph optimised, by the first addFrame() after they end, or by finishLoops(). One
/// keyframe's search runs at a time, in keyframe order; each phase is planned on the graph as it
/// is when it starts, so the searches are those the search in place would make, only later.
///
/// Several sessions (recordings with no known relation between them) go into one graph by
/// startSession() between them: each is tracked on its own, and relocalisation joins it to the
/// others where they share places (sessionLinks() says by how many constraints).
///
/// Memory: every keyframe's segmented view is kept (about 2.5 MB at 640x480: the depth, the
/// labels and the patches) so that it can be registered again later; a LiDAR keyframe's also keeps
/// its returns with their normals (returns_stage.h: 1.5 MB for 16 lasers, 6 MB for 64).
#include <opencv2/core.hpp>

#include <cstddef>
#include <deque>
#include <future>
#include <map>
#include <optional>
#include <vector>

#include "gasp/core/camera_intrinsics.h"
#include "gasp/core/pose.h"
#include "gasp/core/tum_trajectory.h"
#include "gasp/odometry/odometry.h"
#include "gasp/odometry/pose_constraint.h"
#include "gasp/association/place_descriptor.h"
#include "gasp/pipeline/depth_view.h"
#include "gasp/slam/loop_closure.h"
#include "gasp/slam/loop_search.h"
#include "gasp/slam/pose_graph_marginals.h"
#include "gasp/slam/relocalisation.h"
#include "gasp/slam/slam_params.h"

namespace gasp {

class DepthSlam {
 public:
  /// Throws gasp::Error for invalid parameters. T_world_first: the first frame's pose.
  explicit DepthSlam(const SlamParams& params = {}, const Isometry3& T_world_first = Isometry3::Identity());
  ~DepthSlam();  ///< waits for a loop search still running (its results are dropped)
  DepthSlam(const DepthSlam&) = delete;
  DepthSlam& operator=(const DepthSlam&) = delete;

  /// Adds the next frame (DepthOdometry::addFrame(), same errors), then, when it became a
  /// keyframe, searches for loop closures and optimises the graph if one is taken (in the
  /// background: starts or queues the search, and takes a search that has ended).
  const OdometryFrame& addFrame(double timestamp, const cv::Mat& depth_m, const CameraIntrinsics& intrinsics,
                                std::optional<SegmentedDepth> segmented = std::nullopt);
  /// The same for a rotating LiDAR's sweep (DepthOdometry::addFrame(double, const RangeScan&, ...);
  /// lidarSlamParams() are a LiDAR's). Its keyframes keep their returns for the loop closures'
  /// registrations.
  const OdometryFrame& addFrame(double timestamp, const RangeScan& sweep,
                                std::optional<SegmentedDepth> segmented = std::nullopt);
  /// Adds a frame that a DepthOdometry of another process tracked (DepthOdometry::addTracked(),
  /// same errors), then does what addFrame() does after the tracking: its pose in the graph and, for
  /// a keyframe, the loop search. A session replayed so gives the graph that tracking it here would.
  const OdometryFrame& addTracked(TrackedFrame tracked);
  /// Starts a new session (DepthOdometry::startSession()): its frames are tracked on their own,
  /// from T_world_first, and its keyframes searched for loops like any others, so relocalisation
  /// (agreeing votes, relocalisation.h) joins it to the sessions before when they share places,
  /// and never otherwise. A session that is not joined keeps the world it started in.
  void startSession(const Isometry3& T_world_first);
  /// Who registers the loop searches' candidates from now on (loop_search.h; empty:
  /// registerCandidates(), in this process). It must return what registerCandidates() would, as
  /// a log of an earlier run's registrations does (registration_log.h); with background searches it
  /// runs on their thread.
  void setRegistrar(CandidateRegistrar registrar);
  /// Waits for every loop search still running or queued and takes them: afterwards the graph,
  /// poses() and attempts() hold every keyframe's search. Call it after the last frame.
  void finishLoops();
  /// Keyframes whose loop search has not been taken yet (always 0 without background).
  std::size_t loopSearchesPending() const { return waiting_keyframes_.size() + (job_ ? 1 : 0); }

  const DepthOdometry& odometry() const { return odometry_; }
  /// Every frame's pose in the optimised graph (the odometry's until a loop closure is taken).
  /// Frames that no constraint reaches follow their predecessor as the odometry predicted them.
  const std::vector<Isometry3>& poses() const { return T_world_frame_; }
  Trajectory trajectory() const;
  /// The loop closures in the graph (PoseConstraint::loop_closure set), in the order taken.
  const std::vector<PoseConstraint>& loopClosures() const { return loop_closures_; }
  /// The odometry's constraints, then the loop closures: the graph's edges.
  std::vector<PoseConstraint> constraints() const;
  /// The marginal covariance of every frame's pose in the graph (pose_graph_marginals.h): the
  /// uncertainty [t r] of poses()[i] relative to the first frame of its piece (zero there), as the
  /// constraints' informations give it; nullopt for frames no constraint reaches. Computed on
  /// request (a sparse QR over the whole graph).
  PoseGraphMarginals marginals() const;
  /// Every registration tried for a loop closure or relocalisation, in order.
  const std::vector<LoopClosureAttempt>& attempts() const { return attempts_; }
  /// Connected pieces of the graph over all frames (the odometry's componentCount() before
  /// loop closures join pieces).
  std::size_t pieceCount() const;
  /// The loop closures and relocalisations in the graph between each two sessions: links[a][b]
  /// (a < b; symmetric) counts the constraints with one end in session a and the other in b.
  std::vector<std::vector<std::size_t>> sessionLinks() const;
  std::size_t optimisationCount() const { return optimisations_; }
  double optimisationMs() const { return optimisation_ms_; }  ///< total wall time of the optimisations
  const SlamParams& params() const { return params_; }

 private:
  /// One phase of a keyframe's loop search on the background thread (loop_search.h).
  struct LoopJob {
    std::size_t keyframe = 0;
    bool relocalisation = false;  ///< phase 2
    bool taken = false;           ///< phase 1 took a constraint
    std::future<std::vector<LoopRegistration>> registered;
  };
  /// The graph's side of a frame the odometry added: its pose, and when it is a keyframe its loop search.
  const OdometryFrame& added(const OdometryFrame& f);
  /// The graph as the loop search of keyframe k sees it: keyframes up to k.
  LoopSearchGraph graphFor(std::size_t k);
  /// The loop search of a new keyframe in place, then the optimisation when it took any.
  void closeLoops(std::size_t keyframe);
  /// Registers `candidates` to keyframe k on the background thread.
  void startJob(std::size_t k, const std::vector<std::size_t>& candidates, bool relocalisation, bool taken);
  /// Takes the running job when it has ended (or waits for it), plans the next phase or the next
  /// queued keyframe, and so on until a job is running or none is left.
  void takeLoops(bool wait);
  void optimise();

  SlamParams params_;
  DepthOdometry odometry_;
  std::vector<Isometry3> T_world_frame_;
  std::vector<std::size_t> keyframes_;          ///< frame indices, ascending
  std::map<std::size_t, DepthView> keyframe_views_;
  PlaceIndex places_;  ///< the keyframes' place descriptors, when the loop search uses retrieval
  std::vector<PoseConstraint> loop_closures_;
  std::vector<std::size_t> loop_attempt_;       ///< for each loop closure, its index in attempts_
  std::vector<std::size_t> loop_group_;         ///< for each loop closure, its votes' group (0: none)
  std::size_t vote_groups_ = 0;
  std::vector<LoopClosureAttempt> attempts_;
  RelocalisationVotes votes_;                   ///< relocalisations waiting for agreement
  std::size_t optimisations_ = 0;
  double optimisation_ms_ = 0.0;
  CandidateRegistrar registrar_;               ///< empty: registerCandidates()
  std::deque<std::size_t> waiting_keyframes_;  ///< background: keyframes whose search has not started
  std::optional<LoopJob> job_;                 ///< last: destroyed (waited for) before the views it reads
};

}  // namespace gasp
