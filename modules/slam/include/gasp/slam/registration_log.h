#pragma once
/// \file registration_log.h The loop searches' registrations kept, so that a map-building job cut
/// short (killed, out of time) resumes without registering again what it had registered
/// (gasp-slam --checkpoint FILE, --resume).
///
/// Why the registrations are the checkpoint: with the searches in place
/// (LoopClosureParams::background off), the graph is a function of the inputs, the parameters
/// and the registrations -- the tracking, the choice of candidates, the gates, the votes and the
/// optimisations are deterministic, and the registrations are the job's cost. A run whose
/// registrar answers every pair registered before from the log, and registers the others, builds
/// the graph the uninterrupted run builds, without redoing its registrations. (With background
/// searches a run's candidates depend on how far tracking got while a search ran; the log answers
/// whatever it holds, and the graph is the background run's own.)
///
/// The file is a journal: a first line `gasp-registrations 1 FINGERPRINT`, then one line per
/// registration (the keyframe, the candidate, the phase, then the attempt and the constraint,
/// numbers at 17 significant digits so that they read back exactly, tab-separated, the reason
/// last with backslash escapes). Each phase's registrations are appended and flushed to disk as
/// soon as they are made, so a job killed at any moment leaves every phase before it whole; a
/// torn last line (the kill mid-write) is dropped on reading and cut off when the journal is
/// continued. The fingerprint names the job (gasp-slam: the effective parameters, every input
/// option and each input file's size and time): a log answers only the job it was written by.
#include <cstddef>
#include <memory>
#include <string>

#include "gasp/slam/loop_search.h"

namespace gasp {

/// One registration of keyframe `k` to `candidate` (phase: `relocalisation`) as the journal's line
/// (with its newline; also what a process sends back for a registration it made elsewhere).
std::string registrationRecord(std::size_t k, std::size_t candidate, bool relocalisation, const LoopRegistration& r);
/// The same back from a line (without its newline); false when it is not a registration record.
bool readRegistrationRecord(const std::string& line, std::size_t& k, std::size_t& candidate, bool& relocalisation,
                            LoopRegistration& r);

class RegistrationLog {
 public:
  /// An empty log of the job `fingerprint` (any text naming the job's inputs and parameters;
  /// only its hash is kept).
  explicit RegistrationLog(const std::string& fingerprint);
  /// The log in `path`, written by the same job. Throws gasp::Error naming the file when it cannot
  /// be read, is not a registration journal, was written by another job (another fingerprint) or
  /// holds a malformed line (a last line without its newline is the kill's, and dropped).
  static RegistrationLog read(const std::string& path, const std::string& fingerprint);
  /// Whether the file at `path` starts as a registration journal does (any job's); false when it
  /// cannot be read.
  static bool isJournal(const std::string& path);

  /// Writes the log to `path` (a temporary file in its folder, renamed over it) and from then on
  /// appends every registration the registrar makes, flushed to disk after each phase (not those
  /// that failed where they ran, kRegistrationFailed: a resumed job tries them again). Throws
  /// gasp::Error naming the file when it cannot be written; the registrar, later, throws
  /// JobError (loop_search.h), having cut the failed append off.
  void journalTo(const std::string& path);

  /// A registrar (loop_search.h) that answers the pairs the log holds and passes the others to
  /// `inner` (empty: registerCandidates()), logging what it returns. Safe on any one thread at a
  /// time; it shares the log's records (the log may go before it).
  CandidateRegistrar registrar(CandidateRegistrar inner = {}) const;

  std::size_t size() const;        ///< registrations held
  std::size_t answered() const;    ///< registrations the registrar answered from the log
  std::size_t registered() const;  ///< registrations the registrar passed on (and logged)
  /// The fingerprint's hash as the journal's first line holds it (16 hex digits).
  const std::string& fingerprintHash() const;

  struct State;  ///< the records, the counts and the journal (shared with the registrars)

 private:
  std::shared_ptr<State> state_;
};

}  // namespace gasp
