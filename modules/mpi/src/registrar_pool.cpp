#include "gasp/mpi/registrar_pool.h"

#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <limits>
#include <map>
#include <thread>
#include <utility>

#include "gasp/core/error.h"
#include "gasp/pipeline/view_bytes.h"
#include "gasp/slam/registration_log.h"

namespace gasp::mpi {

namespace {

enum Tag : int { kJob = 1, kView = 2, kPair = 3, kRegistration = 4, kStop = 5 };

void send(const std::string& bytes, int to, Tag tag) {
  if (bytes.size() > static_cast<std::size_t>(std::numeric_limits<int>::max()))
    throw JobError("MPI: a message of " + std::to_string(bytes.size()) + " bytes is over MPI's 2 GB count");
  MPI_Send(bytes.data(), static_cast<int>(bytes.size()), MPI_BYTE, to, tag, MPI_COMM_WORLD);
}

/// The next message from `from` (MPI_ANY_SOURCE: any) with `tag` (MPI_ANY_TAG: any). Waits by
/// polling with short sleeps (0.1 ms, growing to 2 ms) rather than in MPI_Probe, which spins a
/// core: an idle rank would take the core that the ranks at work (rank 0 tracking, a rank
/// registering on its threads) share with it.
std::string receive(int from, int tag, MPI_Status& status) {
  int arrived = 0;
  for (auto pause = std::chrono::microseconds(100);; pause = std::min(2 * pause, std::chrono::microseconds(2000))) {
    MPI_Iprobe(from, tag, MPI_COMM_WORLD, &arrived, &status);
    if (arrived) break;
    std::this_thread::sleep_for(pause);
  }
  int count = 0;
  MPI_Get_count(&status, MPI_BYTE, &count);
  std::string bytes(static_cast<std::size_t>(count), '\0');
  MPI_Recv(bytes.data(), count, MPI_BYTE, status.MPI_SOURCE, status.MPI_TAG, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  return bytes;
}

template <class T>
void put(std::string& out, T v) {
  out.append(reinterpret_cast<const char*>(&v), sizeof v);
}
template <class T>
T take(const std::string& in, std::size_t& at) {
  if (in.size() < at + sizeof(T)) throw JobError("MPI: a truncated message");
  T v;
  std::memcpy(&v, in.data() + at, sizeof v);
  at += sizeof v;
  return v;
}

}  // namespace

Session::Session(int& argc, char**& argv) {
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_SERIALIZED, &provided);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
  if (provided < MPI_THREAD_SERIALIZED) {
    MPI_Finalize();
    throw Error("MPI: this MPI library does not give MPI_THREAD_SERIALIZED");
  }
}

Session::~Session() {
  stopWorkers();
  MPI_Finalize();
}

void Session::abort(int code) {
  MPI_Abort(MPI_COMM_WORLD, code);
  std::_Exit(code);  // MPI_Abort does not return; should an MPI return from it, end this rank anyway
}

void Session::stopWorkers() {
  if (rank_ != 0 || stopped_) return;
  stopped_ = true;
  for (int r = 1; r < size_; ++r) send({}, r, kStop);
}

RegistrarPool::RegistrarPool(Session& session, const std::string& job_fingerprint, bool sweeps)
    : session_(session), held_(static_cast<std::size_t>(session.size())) {
  if (session.rank() != 0) throw Error("MPI: the registrar pool is rank 0's");
  std::string job(1, sweeps ? '\1' : '\0');
  job += job_fingerprint;
  for (int r = 1; r < session.size(); ++r) send(job, r, kJob);
}

RegistrarPool::~RegistrarPool() { session_.stopWorkers(); }

CandidateRegistrar RegistrarPool::registrar() {
  return [this](std::size_t k, const DepthView& view_k,
                const std::vector<std::pair<std::size_t, const DepthView*>>& candidates, bool relocalisation,
                const PairParams& pair, const LoopClosureParams& loop) {
    if (session_.size() < 2) return registerCandidates(k, view_k, candidates, relocalisation, pair, loop);
    return spread(k, view_k, candidates, relocalisation);
  };
}

std::vector<LoopRegistration> RegistrarPool::spread(std::size_t k, const DepthView& view_k,
                                                    const std::vector<std::pair<std::size_t, const DepthView*>>& candidates,
                                                    bool relocalisation) {
  std::vector<LoopRegistration> out(candidates.size());
  std::deque<std::size_t> waiting;
  for (std::size_t i = 0; i < candidates.size(); ++i) waiting.push_back(i);
  std::map<int, std::size_t> busy;  // rank -> the candidate it registers
  const auto give = [&](int rank) {
    const std::size_t i = waiting.front();
    waiting.pop_front();
    for (const auto& [index, view] : {std::pair<std::size_t, const DepthView*>{k, &view_k}, candidates[i]}) {
      std::set<std::size_t>& held = held_[static_cast<std::size_t>(rank)];
      if (held.count(index)) continue;
      std::string message;
      put<std::uint64_t>(message, index);
      message += viewBytes(*view);
      send(message, rank, kView);
      held.insert(index);
      ++views_;
      bytes_ += message.size();
    }
    std::string message;
    put<std::uint64_t>(message, k);
    put<std::uint64_t>(message, candidates[i].first);
    put<std::uint8_t>(message, relocalisation ? 1 : 0);
    send(message, rank, kPair);
    ++pairs_;
    busy[rank] = i;
  };
  for (int rank = 1; rank < session_.size() && !waiting.empty(); ++rank) give(rank);
  while (!busy.empty()) {
    MPI_Status status;
    const std::string record = receive(MPI_ANY_SOURCE, kRegistration, status);
    const auto it = busy.find(status.MPI_SOURCE);
    if (it == busy.end()) throw JobError("MPI: a registration from rank " + std::to_string(status.MPI_SOURCE) + ", which had none to make");
    std::size_t rk = 0, candidate = 0;
    bool phase = false;
    LoopRegistration r;
    if (!readRegistrationRecord(record.substr(0, record.size() - 1), rk, candidate, phase, r) || rk != k ||
        candidate != candidates[it->second].first || phase != relocalisation)
      throw JobError("MPI: rank " + std::to_string(status.MPI_SOURCE) + " returned another registration than asked");
    out[it->second] = std::move(r);
    busy.erase(it);
    if (!waiting.empty()) give(status.MPI_SOURCE);
  }
  return out;
}

std::size_t serveRegistrations(const Session& session, const std::string& job_fingerprint, const SlamParams& params,
                               const std::string& job_fingerprint_sweeps, const SlamParams& sweep_params) {
  MPI_Status status;
  std::string job = receive(0, MPI_ANY_TAG, status);
  if (status.MPI_TAG == kStop) return 0;
  if (status.MPI_TAG != kJob || job.empty()) throw Error("MPI: rank 0 sent no job");
  const bool sweeps = job[0] == '\1';
  if (job.substr(1) != (sweeps ? job_fingerprint_sweeps : job_fingerprint))
    throw Error("MPI: rank " + std::to_string(session.rank()) +
                " computed other parameters than rank 0 (every rank must be given the same command line and files)");
  const SlamParams& p = sweeps ? sweep_params : params;
  std::map<std::size_t, DepthView> views;
  std::size_t served = 0;
  for (;;) {
    const std::string message = receive(0, MPI_ANY_TAG, status);
    if (status.MPI_TAG == kStop) return served;
    std::size_t at = 0;
    if (status.MPI_TAG == kView) {
      const auto index = static_cast<std::size_t>(take<std::uint64_t>(message, at));
      views.insert_or_assign(index, viewFromBytes(std::string_view(message).substr(at), p.odometry.pair.segment,
                                                  p.odometry.pair.returns));
      continue;
    }
    if (status.MPI_TAG != kPair) throw Error("MPI: an unknown message tag " + std::to_string(status.MPI_TAG));
    const auto k = static_cast<std::size_t>(take<std::uint64_t>(message, at));
    const auto candidate = static_cast<std::size_t>(take<std::uint64_t>(message, at));
    const bool relocalisation = take<std::uint8_t>(message, at) != 0;
    LoopRegistration r;
    try {
      const auto from = views.find(candidate), to = views.find(k);
      if (from == views.end() || to == views.end()) throw Error("its views were not sent");
      r.attempt = registerLoopClosure(from->second, to->second, candidate, k, relocalisation, p.odometry.pair, p.loop,
                                      r.constraint);
    } catch (const std::exception& e) {  // reported, and the job goes on
      r = LoopRegistration{};
      r.attempt.from = r.constraint.from = candidate;
      r.attempt.to = r.constraint.to = k;
      r.attempt.relocalisation = relocalisation;
      r.constraint.loop_closure = true;
      r.attempt.reason =
          std::string(kRegistrationFailed) + " on rank " + std::to_string(session.rank()) + ": " + e.what();
    }
    send(registrationRecord(k, candidate, relocalisation, r), 0, kRegistration);
    ++served;
  }
}

}  // namespace gasp::mpi
