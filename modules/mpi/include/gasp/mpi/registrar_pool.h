#pragma once
/// \file registrar_pool.h A map-building job spread over MPI processes (gasp-slam --mpi;
/// docs/slam.md "Over many processes"): the sessions tracked on the other ranks, the loop
/// registrations on whichever rank is free.
///
/// Each session is tracked on one rank other than 0 (session s on rank 1 + s mod (N-1)), which
/// hands rank 0 every frame as it tracks it (the program's bytes: odometry.h's TrackedFrame and
/// what else it keeps). Rank 0 replays the sessions in order into the graph -- the loop searches'
/// choice of candidates, the gates, votes and optimisations, the outputs -- as one process does
/// (DepthSlam::addTracked()), and hands each candidate registration to the next free rank
/// (dynamic load balancing: a rank is free once it has tracked its sessions, and gets its next
/// pair when it returns one); while no rank is free, rank 0 registers the pair itself. A rank
/// keeps the frames it has handed over until rank 0 takes them (a session's keyframe views: 2.5 MB
/// each at 640x480). A keyframe's segmented view goes to a rank once, the first time a pair needs it
/// there (view_bytes.h); what comes back is the registration's record (registration_log.h). The
/// registrations are those registerCandidates() makes (the same views, parameters and arithmetic
/// on ranks of the same CPU kind), returned in the candidates' order, so with the searches in
/// place the graph is the single-process job's. A registration that throws on a rank comes back
/// as a failed one (kRegistrationFailed, its reason naming the rank and the error; a journal does
/// not keep it), and the job goes on. A rank that cannot go on at all (other parameters than rank
/// 0's, bytes that are not a view) ends the job with an error naming it (Session::abort), and a
/// protocol error on rank 0 is a JobError (loop_search.h).
///
/// Message tags between rank 0 and the others: the job (its fingerprint, whether its views are
/// sweeps, the sessions and the program's context for tracking them), a tracked frame or a
/// session's end (session, bytes), ready (the rank's sessions are tracked), a view (keyframe
/// index, bytes), a pair (keyframe, candidate, phase), a registration (its record), stop, and the
/// rank's last message (after which it sends nothing).
#include <cstddef>
#include <functional>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <vector>

#include "gasp/slam/loop_search.h"
#include "gasp/slam/slam_params.h"

namespace gasp::mpi {

/// MPI for the process's life (MPI_Init_thread with MPI_THREAD_SERIALIZED: the registrar may run
/// on the background search's thread, one call at a time). On rank 0, the destructor stops the
/// other ranks if no pool did (an error before the job started must not leave them waiting).
class Session {
 public:
  /// Throws gasp::Error when MPI cannot give serialized threads.
  Session(int& argc, char**& argv);
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;
  int rank() const { return rank_; }
  int size() const { return size_; }
  /// Rank 0: tells every other rank to end (once), and takes what they still send until their last
  /// message (a rank stops tracking at its next frame).
  void stopWorkers();
  /// Rank 0: held around each MPI call, which the loop searches' thread and the main thread both
  /// make (MPI_THREAD_SERIALIZED).
  std::mutex& calls() { return calls_; }
  /// A rank other than 0: its last message to rank 0, once (the destructor sends it if nothing
  /// did), for rank 0's stopWorkers() to end on.
  void sendLast();
  /// Ends every rank of the job at once (MPI_Abort): a rank that cannot go on, since the others
  /// would wait for it for ever.
  [[noreturn]] void abort(int code);

 private:
  int rank_ = 0, size_ = 1;
  bool stopped_ = false;
  bool last_sent_ = false;
  std::mutex calls_;
};

/// Thrown on a rank other than 0 by the tracker's `emit` when rank 0 has stopped the job: the
/// tracking ends there (not a gasp::Error: no session's error).
struct JobStopped : std::exception {
  const char* what() const noexcept override { return "the job was stopped"; }
};

/// A rank's tracking of one session (the program's): reads session `session` with the `context`
/// rank 0 gave, calls `emit` with each frame's bytes as it is tracked, and returns the bytes of the
/// session's end (how it ended). A session's error is its end's, not an exception.
using SessionTracker = std::function<std::string(std::size_t session, const std::string& context,
                                                 const std::function<void(std::string)>& emit)>;

/// The rank that tracks session s in a job of `size` ranks (size > 1).
int trackerOf(std::size_t session, int size);

/// Rank 0's side. Sends the job (its fingerprint: any text naming its parameters, which each rank
/// computes itself from the same command line; whether its views are sweeps; `sessions` for the
/// other ranks to track, with the program's `context`) to every other rank when made.
class RegistrarPool {
 public:
  RegistrarPool(Session& session, const std::string& job_fingerprint, bool sweeps, std::size_t sessions = 0,
                const std::string& context = {});
  ~RegistrarPool();  ///< stops the workers
  RegistrarPool(const RegistrarPool&) = delete;
  RegistrarPool& operator=(const RegistrarPool&) = delete;

  /// The registrar (loop_search.h): each candidate to the next free rank; with one process,
  /// registerCandidates() in place. Valid while the pool lives.
  CandidateRegistrar registrar();

  /// Whether the sessions are tracked on the other ranks (sessions given, and more than one rank).
  bool tracksElsewhere() const { return sessions_ > 0 && session_.size() > 1; }
  /// The next message of session s from the rank tracking it, into `message`: true for the
  /// session's end, false for a frame. Take the sessions in order, each to its end. Throws
  /// JobError for a protocol error.
  bool nextTracked(std::size_t s, std::string& message);

  std::size_t pairsSent() const { return pairs_; }
  std::size_t pairsHere() const { return pairs_here_; }  ///< registered on rank 0 while no rank was free
  /// Wall time rank 0 waited for tracked frames in nextTracked() [s]: the job's time less this is
  /// rank 0's own (the replay, its searches and optimisations, its outputs).
  double trackedWaitS() const { return tracked_wait_ms_ / 1000.0; }
  std::size_t viewsSent() const { return views_; }
  double megabytesSent() const { return static_cast<double>(bytes_) / 1e6; }

 private:
  std::vector<LoopRegistration> spread(std::size_t k, const DepthView& view_k,
                                       const std::vector<std::pair<std::size_t, const DepthView*>>& candidates,
                                       bool relocalisation, const PairParams& pair, const LoopClosureParams& loop);
  /// Takes the ready messages that have arrived (non-blocking).
  void takeReady();
  Session& session_;
  std::size_t sessions_ = 0;
  std::vector<std::set<std::size_t>> held_;  ///< the views each rank holds
  std::vector<bool> ready_;                  ///< the ranks that have tracked their sessions
  std::size_t pairs_ = 0, pairs_here_ = 0, views_ = 0, bytes_ = 0;
  double tracked_wait_ms_ = 0.0;
};

/// Another rank's side: receives the job (throws gasp::Error when its fingerprint is not
/// `job_fingerprint`, or, for sweeps, `job_fingerprint_sweeps`), tracks its sessions with `track`
/// (trackerOf()), then registers every pair rank 0 sends with `params` (for sweeps,
/// `sweep_params`) until told to stop. Returns the pairs it registered.
std::size_t serveRegistrations(Session& session, const std::string& job_fingerprint, const SlamParams& params,
                               const std::string& job_fingerprint_sweeps, const SlamParams& sweep_params,
                               const SessionTracker& track = {});

}  // namespace gasp::mpi
