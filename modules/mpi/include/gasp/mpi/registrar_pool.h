#pragma once
/// \file registrar_pool.h A map-building job's loop registrations spread over MPI processes
/// (gasp-slam --mpi; docs/slam.md "Over many processes").
///
/// Rank 0 runs the job as one process does -- the sessions' tracking, the loop searches' choice of
/// candidates, the gates, votes and optimisations, the outputs -- and hands each candidate
/// registration to the next free rank (dynamic load balancing: a rank gets its next pair when it
/// returns one). A keyframe's segmented view goes to a rank once, the first time a pair needs it
/// there (view_bytes.h); what comes back is the registration's record (registration_log.h). The
/// registrations are those registerCandidates() makes (the same views, parameters and arithmetic
/// on ranks of the same CPU kind), returned in the candidates' order, so with the searches in
/// place the graph is the single-process job's. A registration that throws on a rank comes back
/// as a failed one (kRegistrationFailed, its reason naming the rank and the error; a journal does
/// not keep it), and the job goes on. A rank that cannot go on at all (other parameters than rank
/// 0's, bytes that are not a view) ends the job with an error naming it (Session::abort), and a
/// protocol error on rank 0 is a JobError (loop_search.h).
///
/// Message tags between rank 0 and the others: parameters (the job's fingerprint and whether its
/// views are sweeps), a view (keyframe index, bytes), a pair (keyframe, candidate, phase), a
/// registration (its record), stop.
#include <cstddef>
#include <memory>
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
  /// Rank 0: tells every other rank to end (once).
  void stopWorkers();
  /// Ends every rank of the job at once (MPI_Abort): a rank that cannot go on, since the others
  /// would wait for it for ever.
  [[noreturn]] void abort(int code);

 private:
  int rank_ = 0, size_ = 1;
  bool stopped_ = false;
};

/// Rank 0's side. Sends the job (its fingerprint: any text naming its parameters, which each rank
/// computes itself from the same command line, and whether its views are sweeps) to every other
/// rank when made.
class RegistrarPool {
 public:
  RegistrarPool(Session& session, const std::string& job_fingerprint, bool sweeps);
  ~RegistrarPool();  ///< stops the workers
  RegistrarPool(const RegistrarPool&) = delete;
  RegistrarPool& operator=(const RegistrarPool&) = delete;

  /// The registrar (loop_search.h): each candidate to the next free rank; with one process,
  /// registerCandidates() in place. Valid while the pool lives.
  CandidateRegistrar registrar();

  std::size_t pairsSent() const { return pairs_; }
  std::size_t viewsSent() const { return views_; }
  double megabytesSent() const { return static_cast<double>(bytes_) / 1e6; }

 private:
  std::vector<LoopRegistration> spread(std::size_t k, const DepthView& view_k,
                                       const std::vector<std::pair<std::size_t, const DepthView*>>& candidates,
                                       bool relocalisation);
  Session& session_;
  std::vector<std::set<std::size_t>> held_;  ///< the views each rank holds
  std::size_t pairs_ = 0, views_ = 0, bytes_ = 0;
};

/// Another rank's side: receives the job (throws gasp::Error when its fingerprint is not
/// `job_fingerprint`, or, for sweeps, `job_fingerprint_sweeps`), then registers every pair rank 0
/// sends with `params` (for sweeps, `sweep_params`) until told to stop. Returns the pairs it
/// registered.
std::size_t serveRegistrations(const Session& session, const std::string& job_fingerprint, const SlamParams& params,
                               const std::string& job_fingerprint_sweeps, const SlamParams& sweep_params);

}  // namespace gasp::mpi
