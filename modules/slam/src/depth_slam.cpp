#include "gasp/slam/depth_slam.h"

#include <Eigen/Cholesky>

#include <algorithm>
#include <chrono>
#include <string>
#include <utility>

#include "gasp/core/error.h"
#include "gasp/core/format.h"
#include "gasp/core/stopwatch.h"
#include "gasp/pipeline/pair_registration.h"
#include "gasp/slam/pose_graph.h"

namespace gasp {

DepthSlam::DepthSlam(const SlamParams& params, const Isometry3& T_world_first)
    : params_(params), odometry_((validate(params), params.odometry), T_world_first), votes_(params.loop) {}

DepthSlam::~DepthSlam() {
  if (job_ && job_->registered.valid()) job_->registered.wait();
}

const OdometryFrame& DepthSlam::addFrame(double timestamp, const cv::Mat& depth_m, const CameraIntrinsics& intrinsics,
                                         std::optional<SegmentedDepth> segmented) {
  // Throws: nothing added.
  return added(odometry_.addFrame(timestamp, depth_m, intrinsics, std::move(segmented)));
}

const OdometryFrame& DepthSlam::addFrame(double timestamp, const RangeScan& sweep, std::optional<SegmentedDepth> segmented) {
  return added(odometry_.addFrame(timestamp, sweep, std::move(segmented)));  // throws: nothing added
}

const OdometryFrame& DepthSlam::addTracked(TrackedFrame tracked) {
  return added(odometry_.addTracked(std::move(tracked)));  // throws: nothing added
}

const OdometryFrame& DepthSlam::added(const OdometryFrame& f) {
  const std::vector<OdometryFrame>& frames = odometry_.frames();
  if (f.tracked && f.reference != f.index) {
    const PoseConstraint& c = odometry_.constraints().back();  // the one ending in f
    T_world_frame_.push_back(T_world_frame_[c.from] * c.T_from_to);
  } else if (!f.tracked && f.index != odometry_.sessionStarts().back()) {
    // Predicted: follow the predecessor (of the same session) as the odometry did.
    const Isometry3 T_prev_f = frames[f.index - 1].T_world_camera.inverse() * f.T_world_camera;
    T_world_frame_.push_back(T_world_frame_[f.index - 1] * T_prev_f);
  } else {
    T_world_frame_.push_back(f.T_world_camera);  // a session's origin, or its untracked first frame
  }
  if (f.keyframe && params_.loop.enabled) {
    keyframes_.push_back(f.index);
    keyframe_views_.emplace(f.index, *odometry_.keyframeView());
    if (params_.loop.search != LoopSearch::kRadius)
      places_.add(f.index, describeKeyframe(*odometry_.keyframeView(), params_.odometry.pair));
    if (params_.loop.background)
      waiting_keyframes_.push_back(f.index);
    else
      closeLoops(f.index);
  }
  if (params_.loop.background) takeLoops(false);
  return f;
}

void DepthSlam::startSession(const Isometry3& T_world_first) { odometry_.startSession(T_world_first); }

void DepthSlam::finishLoops() { takeLoops(true); }

void DepthSlam::setRegistrar(CandidateRegistrar registrar) {
  takeLoops(true);  // a search running keeps the registrar it started with
  registrar_ = std::move(registrar);
}

void DepthSlam::closeLoops(std::size_t k) {
  if (searchLoops(k, graphFor(k), params_.odometry.pair, params_.loop, attempts_, votes_, vote_groups_)) optimise();
}

void DepthSlam::startJob(std::size_t k, const std::vector<std::size_t>& candidates, bool relocalisation, bool taken) {
  LoopJob job;
  job.keyframe = k;
  job.relocalisation = relocalisation;
  job.taken = taken;
  if (candidates.empty()) {  // nothing to register: ended at once
    std::promise<std::vector<LoopRegistration>> none;
    none.set_value({});
    job.registered = none.get_future();
  } else {
    // The views stay put: keyframe_views_ only grows (std::map keeps its elements in place).
    std::vector<std::pair<std::size_t, const DepthView*>> with_views;
    for (const std::size_t c : candidates) with_views.emplace_back(c, &keyframe_views_.at(c));
    job.registered = std::async(std::launch::async, [k, view_k = &keyframe_views_.at(k), with_views, relocalisation,
                                                     pair = params_.odometry.pair, loop = params_.loop,
                                                     registrar = registrar_] {
      if (registrar) return registrar(k, *view_k, with_views, relocalisation, pair, loop);
      return registerCandidates(k, *view_k, with_views, relocalisation, pair, loop);
    });
  }
  job_ = std::move(job);
}

void DepthSlam::takeLoops(bool wait) {
  for (;;) {
    if (job_) {
      if (!wait && job_->registered.wait_for(std::chrono::seconds(0)) != std::future_status::ready) return;
      LoopJob job = std::move(*job_);
      job_.reset();
      std::vector<LoopRegistration> registered = job.registered.get();
      const LoopSearchGraph g = graphFor(job.keyframe);
      if (!job.relocalisation) {
        const bool taken = takeNearLoops(job.keyframe, g, std::move(registered), params_.loop, attempts_);
        const std::vector<std::size_t> relocalisation = relocalisationCandidatesOf(job.keyframe, g, params_.loop);
        if (!relocalisation.empty()) {
          startJob(job.keyframe, relocalisation, true, taken);
          continue;
        }
        if (taken) optimise();
      } else if (takeRelocalisations(job.keyframe, g, std::move(registered), attempts_, votes_, vote_groups_) ||
                 job.taken) {
        optimise();
      }
      continue;
    }
    if (waiting_keyframes_.empty()) return;
    const std::size_t k = waiting_keyframes_.front();
    waiting_keyframes_.pop_front();
    startJob(k, nearLoopCandidates(k, graphFor(k), params_.loop), false, false);
  }
}

LoopSearchGraph DepthSlam::graphFor(std::size_t k) {
  LoopSearchGraph g;
  g.node_count = T_world_frame_.size();
  g.keyframes.assign(keyframes_.begin(), std::upper_bound(keyframes_.begin(), keyframes_.end(), k));
  g.T_world_camera = T_world_frame_;
  g.tree = odometry_.constraints();
  g.view = [this](std::size_t i) -> const DepthView& { return keyframe_views_.at(i); };
  g.links = [this] { return constraints(); };
  g.retrieve = [this](std::size_t key) { return retrieveEarlier(places_, key); };
  g.register_candidates = registrar_;
  g.insert = [this](const PoseConstraint& c, std::size_t attempt, std::size_t group) {
    loop_closures_.push_back(c);
    loop_attempt_.push_back(attempt);
    loop_group_.push_back(group);
  };
  // Before a join, the later piece (the larger root) moves rigidly onto the newest vote, so the
  // optimiser starts near the answer and the piece holding frame 0 keeps its place (the gauge).
  g.before_join = [this](const PoseConstraint& newest, const RelocalisationVotes::Decision&,
                         const std::vector<std::size_t>& roots) {
    const std::size_t from = newest.from, to = newest.to;
    const Isometry3 T_fix = T_world_frame_[from] * newest.T_from_to * T_world_frame_[to].inverse();
    const std::size_t moved = std::max(roots[from], roots[to]);
    const Isometry3 T_move = roots[to] == moved ? T_fix : T_fix.inverse();
    for (std::size_t i = 0; i < T_world_frame_.size(); ++i)
      if (roots[i] == moved) T_world_frame_[i] = T_move * T_world_frame_[i];
    return std::string();
  };
  return g;
}

void DepthSlam::optimise() {
  const auto t0 = std::chrono::steady_clock::now();
  const std::vector<OdometryFrame>& frames = odometry_.frames();
  for (;;) {
    const std::vector<PoseConstraint> edges = constraints();
    const PoseGraphResult r = optimizePoseGraph(T_world_frame_, edges, params_.graph);
    ++optimisations_;
    T_world_frame_ = r.T_world_node;
    // Frames no constraint reaches follow their predecessor in the session, as the odometry
    // predicted them (a session's first frame keeps its place).
    std::vector<bool> linked(T_world_frame_.size(), false);
    for (const PoseConstraint& c : edges) linked[c.from] = linked[c.to] = true;
    for (std::size_t i = 1; i < T_world_frame_.size(); ++i)
      if (!linked[i] && frames[i].session == frames[i - 1].session)
        T_world_frame_[i] = T_world_frame_[i - 1] * (frames[i - 1].T_world_camera.inverse() * frames[i].T_world_camera);
    // A session's frames before its first linked one (no patches yet) go with it, wherever a
    // join has moved it.
    const std::vector<std::size_t>& starts = odometry_.sessionStarts();
    for (std::size_t s = 0; s < starts.size(); ++s) {
      const std::size_t end = s + 1 < starts.size() ? starts[s + 1] : T_world_frame_.size();
      std::size_t first_linked = starts[s];
      while (first_linked < end && !linked[first_linked]) ++first_linked;
      for (std::size_t j = first_linked; first_linked < end && j-- > starts[s];)
        T_world_frame_[j] = T_world_frame_[j + 1] * (frames[j + 1].T_world_camera.inverse() * frames[j].T_world_camera);
    }
    // Drop the closure the optimised graph contradicts most, if any does, and optimise again.
    const std::optional<Contradiction> contradiction =
        mostContradictedClosure(T_world_frame_, loop_closures_, params_.loop.gate_chi2);
    if (!contradiction) break;
    const std::size_t worst = contradiction->edge;
    const double worst_chi2 = contradiction->chi2;
    std::vector<std::size_t> drop{worst};
    // The votes that joined two pieces go together once fewer than relocalisation_agreeing are
    // left: one of them alone would be the unchecked join the votes exist to prevent.
    if (const std::size_t group = loop_group_[worst]; group != 0) {
      std::vector<std::size_t> rest;
      for (std::size_t j = 0; j < loop_closures_.size(); ++j)
        if (j != worst && loop_group_[j] == group) rest.push_back(j);
      if (rest.size() < params_.loop.relocalisation_agreeing) drop.insert(drop.end(), rest.begin(), rest.end());
    }
    for (const std::size_t j : drop) {
      LoopClosureAttempt& a = attempts_[loop_attempt_[j]];
      a.accepted = false;
      a.reason = j == worst ? formatted("dropped: the optimised graph contradicts it (chi-square %.1f > %.2f)",
                                        worst_chi2, params_.loop.gate_chi2)
                            : "dropped: a vote it joined two pieces with was contradicted, too few are left";
    }
    std::sort(drop.rbegin(), drop.rend());  // erase from the back, so the positions stay valid
    for (const std::size_t j : drop) {
      loop_closures_.erase(loop_closures_.begin() + static_cast<std::ptrdiff_t>(j));
      loop_attempt_.erase(loop_attempt_.begin() + static_cast<std::ptrdiff_t>(j));
      loop_group_.erase(loop_group_.begin() + static_cast<std::ptrdiff_t>(j));
    }
  }
  optimisation_ms_ += msSince(t0);
}

PoseGraphMarginals DepthSlam::marginals() const {
  return poseGraphMarginals(T_world_frame_, constraints(), params_.graph.num_threads);
}

std::vector<PoseConstraint> DepthSlam::constraints() const {
  std::vector<PoseConstraint> all = odometry_.constraints();
  all.insert(all.end(), loop_closures_.begin(), loop_closures_.end());
  return all;
}

Trajectory DepthSlam::trajectory() const {
  Trajectory t;
  t.reserve(T_world_frame_.size());
  const std::vector<OdometryFrame>& frames = odometry_.frames();
  for (std::size_t i = 0; i < frames.size(); ++i) t.push_back({frames[i].timestamp, T_world_frame_[i]});
  return t;
}

std::vector<std::vector<std::size_t>> DepthSlam::sessionLinks() const {
  const std::vector<OdometryFrame>& frames = odometry_.frames();
  const std::size_t n = odometry_.sessionStarts().size();
  std::vector<std::vector<std::size_t>> links(n, std::vector<std::size_t>(n, 0));
  for (const PoseConstraint& c : loop_closures_) {
    const std::size_t a = frames[c.from].session, b = frames[c.to].session;
    if (a == b) continue;
    ++links[a][b];
    ++links[b][a];
  }
  return links;
}

std::size_t DepthSlam::pieceCount() const { return gasp::pieceCount(T_world_frame_.size(), constraints()); }

}  // namespace gasp
