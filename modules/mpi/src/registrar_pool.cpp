#include "gasp/mpi/registrar_pool.h"

#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <deque>
#include <limits>
#include <list>
#include <map>
#include <thread>
#include <utility>

#include "gasp/core/byte_stream.h"
#include "gasp/core/error.h"
#include "gasp/pipeline/view_bytes.h"
#include "gasp/slam/registration_log.h"

namespace gasp::mpi {

namespace {

enum Tag : int { kJob = 1, kView = 2, kPair = 3, kRegistration = 4, kStop = 5, kTracked = 6, kReady = 7 };
/// A kTracked message's kind: a frame, a session's end, the rank's last message.
enum Kind : std::uint8_t { kFrame = 0, kEnd = 1, kLast = 2 };
/// A kTracked message's head: its session (8 bytes), then its kind (1 byte).
constexpr std::size_t kTrackedHead = sizeof(std::uint64_t) + 1;

/// Held around one MPI call on rank 0 (nullptr elsewhere: one thread calls MPI).
class Calls {
 public:
  explicit Calls(std::mutex* m) : m_(m) {
    if (m_) m_->lock();
  }
  ~Calls() {
    if (m_) m_->unlock();
  }
  Calls(const Calls&) = delete;
  Calls& operator=(const Calls&) = delete;

 private:
  std::mutex* m_;
};

int count(const std::string& bytes) {
  if (bytes.size() > static_cast<std::size_t>(std::numeric_limits<int>::max()))
    throw JobError("MPI: a message of " + std::to_string(bytes.size()) + " bytes is over MPI's 2 GB count");
  return static_cast<int>(bytes.size());
}

void send(const std::string& bytes, int to, Tag tag, std::mutex* calls = nullptr) {
  const int n = count(bytes);
  Calls held(calls);
  MPI_Send(bytes.data(), n, MPI_BYTE, to, tag, MPI_COMM_WORLD);
}

/// The message that has arrived from `from` (MPI_ANY_SOURCE: any) with `tag` (MPI_ANY_TAG: any),
/// if one has.
bool tryReceive(int from, int tag, MPI_Status& status, std::string& bytes, std::mutex* calls) {
  Calls held(calls);
  int arrived = 0;
  MPI_Iprobe(from, tag, MPI_COMM_WORLD, &arrived, &status);
  if (!arrived) return false;
  int n = 0;
  MPI_Get_count(&status, MPI_BYTE, &n);
  bytes.assign(static_cast<std::size_t>(n), '\0');
  MPI_Recv(bytes.data(), n, MPI_BYTE, status.MPI_SOURCE, status.MPI_TAG, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  return true;
}

/// The next message from `from` with `tag`. Waits by polling with short sleeps (0.1 ms, growing to
/// 2 ms) rather than in MPI_Probe, which spins a core: an idle rank would take the core that the
/// ranks at work share with it. `between`: called between polls.
std::string receive(int from, int tag, MPI_Status& status, std::mutex* calls = nullptr,
                    const std::function<void()>& between = {}) {
  std::string bytes;
  for (auto pause = std::chrono::microseconds(100);; pause = std::min(2 * pause, std::chrono::microseconds(2000))) {
    if (tryReceive(from, tag, status, bytes, calls)) return bytes;
    if (between) between();
    std::this_thread::sleep_for(pause);
  }
}

/// A rank's messages to rank 0 that may be large (tracked frames), sent without waiting for rank 0
/// to take them: each is kept until its send completes.
class Outbox {
 public:
  void post(std::string bytes) {
    const int n = count(bytes);
    held_ += bytes.size();
    sent_.push_back({std::move(bytes), MPI_REQUEST_NULL});
    MPI_Isend(sent_.back().bytes.data(), n, MPI_BYTE, 0, kTracked, MPI_COMM_WORLD, &sent_.back().request);
  }
  /// Drops the messages rank 0 has taken.
  void collect() {
    for (auto it = sent_.begin(); it != sent_.end();) {
      int done = 0;
      MPI_Test(&it->request, &done, MPI_STATUS_IGNORE);
      if (done) held_ -= it->bytes.size();
      it = done ? sent_.erase(it) : std::next(it);
    }
  }
  std::size_t held() const { return held_; }  ///< bytes rank 0 has not taken yet
  /// Waits for rank 0 to take every message (it does, up to the rank's last: Session::stopWorkers()).
  void flush() {
    for (Message& m : sent_) MPI_Wait(&m.request, MPI_STATUS_IGNORE);
    sent_.clear();
    held_ = 0;
  }

 private:
  struct Message {
    std::string bytes;
    MPI_Request request;
  };
  std::list<Message> sent_;  // a list: the buffers stay put while MPI sends them
  std::size_t held_ = 0;
};

/// At most this many bytes of tracked frames wait on a rank for rank 0 to take them (about 400
/// keyframe views at 640 x 480); a rank further ahead waits.
constexpr std::size_t kMaxHeldBytes = std::size_t{1} << 30;

std::string tracked(std::size_t session, Kind kind, const std::string& payload) {
  ByteWriter w;
  w.putSize(session);
  w.put(static_cast<std::uint8_t>(kind));
  std::string bytes = w.take();
  bytes += payload;
  return bytes;
}

}  // namespace

int trackerOf(std::size_t session, int size) {
  return 1 + static_cast<int>(session % static_cast<std::size_t>(std::max(1, size - 1)));
}

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
  try {
    stopWorkers();
    sendLast();
  } catch (const std::exception&) {  // a protocol error while stopping: end every rank
    abort(1);
  }
  MPI_Finalize();
}

void Session::sendLast() {
  if (rank_ == 0 || last_sent_) return;
  last_sent_ = true;
  send(tracked(0, kLast, {}), 0, kTracked);
}

void Session::abort(int code) {
  MPI_Abort(MPI_COMM_WORLD, code);
  std::_Exit(code);  // MPI_Abort does not return; should an MPI return from it, end this rank anyway
}

void Session::stopWorkers() {
  if (rank_ != 0 || stopped_) return;
  stopped_ = true;
  for (int r = 1; r < size_; ++r) send({}, r, kStop, &calls_);
  // Everything a rank still sends -- frames rank 0 did not take, its ready message -- up to its
  // last message: its sends then complete, and it can end.
  for (int r = 1; r < size_; ++r)
    for (;;) {
      MPI_Status status;
      const std::string bytes = receive(r, MPI_ANY_TAG, status, &calls_);
      if (status.MPI_TAG == kTracked && bytes.size() >= kTrackedHead &&
          static_cast<std::uint8_t>(bytes[kTrackedHead - 1]) == kLast) break;
    }
}

RegistrarPool::RegistrarPool(Session& session, const std::string& job_fingerprint, bool sweeps, std::size_t sessions,
                             const std::string& context)
    : session_(session), sessions_(sessions), held_(static_cast<std::size_t>(session.size())),
      ready_(static_cast<std::size_t>(session.size()), sessions == 0) {
  if (session.rank() != 0) throw Error("MPI: the registrar pool is rank 0's");
  ByteWriter w;
  w.putFlag(sweeps);
  w.putSize(sessions);
  w.putString(context);
  w.putString(job_fingerprint);
  const std::string job = w.take();
  for (int r = 1; r < session.size(); ++r) send(job, r, kJob, &session_.calls());
}

RegistrarPool::~RegistrarPool() {
  try {
    session_.stopWorkers();
  } catch (const std::exception&) {
    session_.abort(1);
  }
}

CandidateRegistrar RegistrarPool::registrar() {
  return [this](std::size_t k, const DepthView& view_k,
                const std::vector<std::pair<std::size_t, const DepthView*>>& candidates, bool relocalisation,
                const PairParams& pair, const LoopClosureParams& loop) {
    if (session_.size() < 2) return registerCandidates(k, view_k, candidates, relocalisation, pair, loop);
    return spread(k, view_k, candidates, relocalisation, pair, loop);
  };
}

bool RegistrarPool::nextTracked(std::size_t s, std::string& message) {
  if (!tracksElsewhere() || s >= sessions_) throw JobError("MPI: session " + std::to_string(s) + " is not tracked elsewhere");
  const int from = trackerOf(s, session_.size());
  MPI_Status status;
  const auto t0 = std::chrono::steady_clock::now();
  const std::string bytes = receive(from, kTracked, status, &session_.calls());
  tracked_wait_ms_ += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  ByteReader r(bytes, "MPI: rank " + std::to_string(from) + "'s tracked frame");
  std::size_t session = 0;
  std::uint8_t kind = 0;
  try {
    session = r.getSize(0, "its session");
    kind = r.get<std::uint8_t>("its kind");
  } catch (const Error& e) {
    throw JobError(e.what());
  }
  if (session != s || kind > kEnd)
    throw JobError("MPI: rank " + std::to_string(from) + " sent another session's frame than " + std::to_string(s));
  message = bytes.substr(kTrackedHead);
  return kind == kEnd;
}

void RegistrarPool::takeReady() {
  MPI_Status status;
  std::string bytes;
  while (tryReceive(MPI_ANY_SOURCE, kReady, status, bytes, &session_.calls()))
    ready_[static_cast<std::size_t>(status.MPI_SOURCE)] = true;
}

std::vector<LoopRegistration> RegistrarPool::spread(std::size_t k, const DepthView& view_k,
                                                    const std::vector<std::pair<std::size_t, const DepthView*>>& candidates,
                                                    bool relocalisation, const PairParams& pair,
                                                    const LoopClosureParams& loop) {
  std::mutex* calls = &session_.calls();
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
      ByteWriter w;
      w.putSize(index);
      std::string message = w.take();
      message += viewBytes(*view);
      send(message, rank, kView, calls);
      held.insert(index);
      ++views_;
      bytes_ += message.size();
    }
    ByteWriter w;
    w.putSize(k);
    w.putSize(candidates[i].first);
    w.putFlag(relocalisation);
    send(w.take(), rank, kPair, calls);
    ++pairs_;
    busy[rank] = i;
  };
  const auto take = [&](const std::string& record, int rank) {
    const auto it = busy.find(rank);
    if (it == busy.end()) throw JobError("MPI: a registration from rank " + std::to_string(rank) + ", which had none to make");
    std::size_t rk = 0, candidate = 0;
    bool phase = false;
    LoopRegistration r;
    if (record.empty() || !readRegistrationRecord(record.substr(0, record.size() - 1), rk, candidate, phase, r) ||
        rk != k || candidate != candidates[it->second].first || phase != relocalisation)
      throw JobError("MPI: rank " + std::to_string(rank) + " returned another registration than asked");
    out[it->second] = std::move(r);
    busy.erase(it);
  };
  while (!waiting.empty() || !busy.empty()) {
    takeReady();
    for (int rank = 1; rank < session_.size() && !waiting.empty(); ++rank)
      if (ready_[static_cast<std::size_t>(rank)] && !busy.count(rank)) give(rank);
    MPI_Status status;
    std::string record;
    if (!waiting.empty()) {
      // No rank is free (they are tracking, or all registering): this one registers a pair, then
      // takes what has come back.
      const std::size_t i = waiting.front();
      waiting.pop_front();
      out[i] = registerCandidate(k, view_k, candidates[i].first, *candidates[i].second, relocalisation, pair, loop,
                                 " on rank 0");
      ++pairs_here_;
      while (tryReceive(MPI_ANY_SOURCE, kRegistration, status, record, calls)) take(record, status.MPI_SOURCE);
      continue;
    }
    record = receive(MPI_ANY_SOURCE, kRegistration, status, calls);
    take(record, status.MPI_SOURCE);
  }
  return out;
}

std::size_t serveRegistrations(Session& session, const std::string& job_fingerprint, const SlamParams& params,
                               const std::string& job_fingerprint_sweeps, const SlamParams& sweep_params,
                               const SessionTracker& track) {
  Outbox outbox;
  std::size_t served = 0;
  MPI_Status status;
  // Rank 0 stopped the job: its last message, once everything before it is taken.
  const auto stopped = [&] {
    outbox.flush();
    session.sendLast();
    return served;
  };
  const std::string job = receive(0, MPI_ANY_TAG, status);
  if (status.MPI_TAG == kStop) return stopped();
  if (status.MPI_TAG != kJob) throw Error("MPI: rank 0 sent no job");
  ByteReader r(job, "MPI: rank 0's job");
  const bool sweeps = r.getFlag("its sensor");
  const std::size_t sessions = r.getSize(1, "its sessions");
  const std::string context = r.getString("its context");
  if (r.getString("its fingerprint") != (sweeps ? job_fingerprint_sweeps : job_fingerprint))
    throw Error("MPI: rank " + std::to_string(session.rank()) +
                " computed other parameters than rank 0 (every rank must be given the same command line and files)");
  const SlamParams& p = sweeps ? sweep_params : params;

  // The sessions this rank tracks, each frame handed to rank 0 as it is tracked; a stop from rank
  // 0 ends the tracking at the next frame.
  if (sessions > 0) {
    if (!track) throw Error("MPI: rank 0 asks for sessions to be tracked, and this program tracks none");
    const auto stop_asked = [&] {
      MPI_Status st;
      std::string none;
      return tryReceive(0, kStop, st, none, nullptr);
    };
    try {
      for (std::size_t s = 0; s < sessions; ++s) {
        if (trackerOf(s, session.size()) != session.rank()) continue;
        if (stop_asked()) throw JobStopped();
        const std::string end = track(s, context, [&](std::string frame) {
          for (outbox.collect(); outbox.held() > kMaxHeldBytes; outbox.collect()) {
            if (stop_asked()) throw JobStopped();
            std::this_thread::sleep_for(std::chrono::milliseconds(2));
          }
          if (stop_asked()) throw JobStopped();
          outbox.post(tracked(s, kFrame, frame));
        });
        outbox.post(tracked(s, kEnd, end));
      }
      if (stop_asked()) throw JobStopped();
    } catch (const JobStopped&) {
      return stopped();
    }
    send({}, 0, kReady);
  }

  std::map<std::size_t, DepthView> views;
  for (;;) {
    const std::string message = receive(0, MPI_ANY_TAG, status, nullptr, [&] { outbox.collect(); });
    if (status.MPI_TAG == kStop) return stopped();
    ByteReader m(message, "MPI: rank 0's message");
    if (status.MPI_TAG == kView) {
      const std::size_t index = m.getSize(0, "the view's keyframe");
      views.insert_or_assign(index, viewFromBytes(std::string_view(message).substr(sizeof(std::uint64_t)), p.odometry.pair.segment,
                                                  p.odometry.pair.returns));
      continue;
    }
    if (status.MPI_TAG != kPair) throw Error("MPI: an unknown message tag " + std::to_string(status.MPI_TAG));
    const std::size_t k = m.getSize(0, "the pair");
    const std::size_t candidate = m.getSize(0, "the pair");
    const bool relocalisation = m.getFlag("the pair");
    const auto from = views.find(candidate), to = views.find(k);
    if (from == views.end() || to == views.end()) throw Error("MPI: a pair whose views were not sent");
    const LoopRegistration reg = registerCandidate(k, to->second, candidate, from->second, relocalisation,
                                                   p.odometry.pair, p.loop, " on rank " + std::to_string(session.rank()));
    send(registrationRecord(k, candidate, relocalisation, reg), 0, kRegistration);
    ++served;
  }
}

}  // namespace gasp::mpi
