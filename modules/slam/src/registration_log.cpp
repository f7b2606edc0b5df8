#include "gasp/slam/registration_log.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cinttypes>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <mutex>
#include <sstream>
#include <tuple>
#include <vector>

#include "gasp/core/error.h"
#include "gasp/core/output_file.h"

namespace gasp {

namespace {

constexpr const char* kMagic = "gasp-registrations";
constexpr int kVersion = 1;

/// FNV-1a, 64 bits: stable across builds and machines (std::hash is not).
std::string hashOf(const std::string& text) {
  std::uint64_t h = 1469598103934665603ull;
  for (const unsigned char c : text) h = (h ^ c) * 1099511628211ull;
  char out[17];
  std::snprintf(out, sizeof out, "%016" PRIx64, h);
  return out;
}

std::string escaped(const std::string& s) {
  std::string out;
  for (const char c : s) {
    if (c == '\\') out += "\\\\";
    else if (c == '\t') out += "\\t";
    else if (c == '\n') out += "\\n";
    else if (c == '\r') out += "\\r";
    else out += c;
  }
  return out;
}

bool unescaped(const std::string& s, std::string& out) {
  out.clear();
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] != '\\') {
      out += s[i];
      continue;
    }
    if (++i >= s.size()) return false;
    switch (s[i]) {
      case '\\': out += '\\'; break;
      case 't': out += '\t'; break;
      case 'n': out += '\n'; break;
      case 'r': out += '\r'; break;
      default: return false;
    }
  }
  return true;
}

/// The pair a registration answers: the keyframe, the candidate, the phase.
using Key = std::tuple<std::size_t, std::size_t, bool>;

void appendNumber(std::string& line, double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "\t%.17g", v);
  line += buf;
}
void appendNumber(std::string& line, std::size_t v) { line += "\t" + std::to_string(v); }
void appendNumber(std::string& line, int v) { line += "\t" + std::to_string(v); }

/// One journal line (with its newline).
std::string recordLine(const Key& key, const LoopRegistration& r) {
  std::string line = "R";
  appendNumber(line, std::get<0>(key));
  appendNumber(line, std::get<1>(key));
  appendNumber(line, static_cast<int>(std::get<2>(key)));
  const LoopClosureAttempt& a = r.attempt;
  appendNumber(line, a.from);
  appendNumber(line, a.to);
  appendNumber(line, static_cast<int>(a.relocalisation));
  appendNumber(line, static_cast<int>(a.accepted));
  appendNumber(line, a.inliers);
  appendNumber(line, a.gate_chi2);
  appendNumber(line, a.registration_ms);
  const PoseConstraint& c = r.constraint;
  appendNumber(line, c.from);
  appendNumber(line, c.to);
  for (int row = 0; row < 3; ++row)
    for (int col = 0; col < 4; ++col) appendNumber(line, c.T_from_to.matrix()(row, col));
  for (int i = 0; i < 36; ++i) appendNumber(line, c.information(i / 6, i % 6));
  appendNumber(line, c.inliers);
  appendNumber(line, static_cast<int>(c.loop_closure));
  appendNumber(line, static_cast<int>(c.scene_change));
  appendNumber(line, c.free_directions);
  line += "\t" + escaped(a.reason) + "\n";
  return line;
}

constexpr std::size_t kFields = 1 + 3 + 7 + 2 + 12 + 36 + 4 + 1;

/// Parses one journal line (without its newline); false when malformed.
bool parseRecord(const std::string& line, Key& key, LoopRegistration& r) {
  std::vector<std::string> f;
  std::size_t start = 0;
  for (;;) {
    const std::size_t tab = line.find('\t', start);
    f.push_back(line.substr(start, tab == std::string::npos ? std::string::npos : tab - start));
    if (tab == std::string::npos) break;
    start = tab + 1;
  }
  if (f.size() != kFields || f[0] != "R") return false;
  std::size_t i = 1;
  bool ok = true;
  const auto size = [&]() -> std::size_t {
    const std::string& s = f[i++];
    char* end = nullptr;
    errno = 0;
    const unsigned long long v = std::strtoull(s.c_str(), &end, 10);
    ok = ok && !s.empty() && s[0] != '-' && end && *end == '\0' && errno == 0;
    return static_cast<std::size_t>(v);
  };
  const auto integer = [&]() -> int {
    const std::string& s = f[i++];
    char* end = nullptr;
    errno = 0;
    const long v = std::strtol(s.c_str(), &end, 10);
    ok = ok && !s.empty() && end && *end == '\0' && errno == 0 && v >= -2147483647L && v <= 2147483647L;
    return static_cast<int>(v);
  };
  const auto flag = [&]() -> bool {
    const int v = integer();
    ok = ok && (v == 0 || v == 1);
    return v == 1;
  };
  const auto real = [&]() -> double {
    const std::string& s = f[i++];
    char* end = nullptr;
    const double v = std::strtod(s.c_str(), &end);
    ok = ok && !s.empty() && end && *end == '\0';
    return v;
  };
  const std::size_t k = size(), from = size();
  const bool relocalisation = flag();
  key = Key{k, from, relocalisation};
  LoopClosureAttempt& a = r.attempt;
  a.from = size();
  a.to = size();
  a.relocalisation = flag();
  a.accepted = flag();
  a.inliers = integer();
  a.gate_chi2 = real();
  a.registration_ms = real();
  PoseConstraint& c = r.constraint;
  c.from = size();
  c.to = size();
  Eigen::Matrix4d M = Eigen::Matrix4d::Identity();
  for (int row = 0; row < 3; ++row)
    for (int col = 0; col < 4; ++col) M(row, col) = real();
  c.T_from_to.matrix() = M;
  for (int j = 0; j < 36; ++j) c.information(j / 6, j % 6) = real();
  c.inliers = integer();
  c.loop_closure = flag();
  c.scene_change = flag();
  c.free_directions = integer();
  ok = ok && unescaped(f[i], a.reason);
  return ok;
}

std::string headerLine(const std::string& hash) {
  return std::string(kMagic) + " " + std::to_string(kVersion) + " " + hash + "\n";
}

}  // namespace

std::string registrationRecord(std::size_t k, std::size_t candidate, bool relocalisation, const LoopRegistration& r) {
  return recordLine(Key{k, candidate, relocalisation}, r);
}

bool readRegistrationRecord(const std::string& line, std::size_t& k, std::size_t& candidate, bool& relocalisation,
                            LoopRegistration& r) {
  Key key;
  if (!parseRecord(line, key, r)) return false;
  std::tie(k, candidate, relocalisation) = key;
  return true;
}

struct RegistrationLog::State {
  std::string hash;
  mutable std::mutex mutex;
  std::map<Key, LoopRegistration> records;
  std::vector<Key> order;  ///< the records in the order made (the journal's)
  std::size_t answered = 0, registered = 0;
  std::string journal_path;
  int journal_fd = -1;
  std::string journal_failed;  ///< why the journal stopped (every later append is refused)

  ~State() {
    if (journal_fd >= 0) ::close(journal_fd);
  }

  /// Appends `text` to the journal and flushes it to disk. A failed append is cut off again (the
  /// journal keeps whole records only), the journal is closed, and this and every later append
  /// throw JobError naming the file.
  void append(const std::string& text) {
    if (!journal_failed.empty()) throw JobError(journal_failed);
    if (journal_fd < 0) return;
    const off_t before = ::lseek(journal_fd, 0, SEEK_END);
    std::size_t done = 0;
    std::string why;
    while (done < text.size() && why.empty()) {
      const ssize_t n = ::write(journal_fd, text.data() + done, text.size() - done);
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) why = std::strerror(errno);
      else if (n == 0) why = "nothing written";
      else done += static_cast<std::size_t>(n);
    }
    if (why.empty() && ::fsync(journal_fd) != 0) why = std::strerror(errno);
    if (why.empty()) return;
    if (before >= 0) (void)::ftruncate(journal_fd, before);
    ::close(journal_fd);
    journal_fd = -1;
    journal_failed = "cannot write registration journal '" + journal_path + "': " + why;
    throw JobError(journal_failed);
  }
};

RegistrationLog::RegistrationLog(const std::string& fingerprint) : state_(std::make_shared<State>()) {
  state_->hash = hashOf(fingerprint);
}

RegistrationLog RegistrationLog::read(const std::string& path, const std::string& fingerprint) {
  RegistrationLog log(fingerprint);
  std::error_code ec;
  if (std::filesystem::exists(path, ec) && !std::filesystem::is_regular_file(path, ec))
    throw Error("cannot read registration journal '" + path + "': not a regular file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error("cannot read registration journal '" + path + "': " + std::strerror(errno));
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw Error("cannot read registration journal '" + path + "'");
  const std::size_t first = text.find('\n');
  std::istringstream header(text.substr(0, first));
  std::string magic, hash;
  int version = 0;
  header >> magic >> version >> hash;
  if (first == std::string::npos || magic != kMagic || version != kVersion || hash.size() != 16)
    throw Error("'" + path + "' is not a GASP registration journal (expected a first line '" + kMagic + " " +
                std::to_string(kVersion) + " <16 hex digits>')");
  if (hash != log.state_->hash)
    throw Error("registration journal '" + path + "' is another job's (its inputs or parameters differ: fingerprint " +
                hash + ", this job's " + log.state_->hash + "); start without --resume, or give another checkpoint");
  std::size_t at = first + 1, line_number = 1;
  while (at < text.size()) {
    ++line_number;
    const std::size_t end = text.find('\n', at);
    if (end == std::string::npos) break;  // a torn last line: the kill mid-write
    Key key;
    LoopRegistration r;
    if (!parseRecord(text.substr(at, end - at), key, r)) {
      throw Error("registration journal '" + path + "', line " + std::to_string(line_number) +
                  ": not a registration record (" + std::to_string(kFields) + " tab-separated fields expected)");
    }
    if (log.state_->records.emplace(key, std::move(r)).second) log.state_->order.push_back(key);
    at = end + 1;
  }
  return log;
}

bool RegistrationLog::isJournal(const std::string& path) {
  // A regular file's first bytes only: a device (/dev/zero) never ends.
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return false;
  std::ifstream in(path, std::ios::binary);
  const std::string magic = kMagic;
  std::string head(magic.size() + 1, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  return head.size() == magic.size() + 1 && head.compare(0, magic.size(), magic) == 0 &&
         (head.back() == ' ' || head.back() == '\n');
}

void RegistrationLog::journalTo(const std::string& path) {
  std::lock_guard<std::mutex> lock(state_->mutex);
  std::string text = headerLine(state_->hash);
  for (const Key& key : state_->order) text += recordLine(key, state_->records.at(key));
  writeWholeFile(path, text, "registration journal");
  const int fd = ::open(path.c_str(), O_WRONLY | O_APPEND | O_CLOEXEC);
  if (fd < 0) throw Error("cannot write registration journal '" + path + "': " + std::strerror(errno));
  if (state_->journal_fd >= 0) ::close(state_->journal_fd);
  state_->journal_fd = fd;
  state_->journal_path = path;
  state_->journal_failed.clear();
}

CandidateRegistrar RegistrationLog::registrar(CandidateRegistrar inner) const {
  return [state = state_, inner = std::move(inner)](
             std::size_t k, const DepthView& view_k,
             const std::vector<std::pair<std::size_t, const DepthView*>>& candidates, bool relocalisation,
             const PairParams& pair, const LoopClosureParams& loop) {
    std::vector<LoopRegistration> out(candidates.size());
    std::vector<std::pair<std::size_t, const DepthView*>> missing;
    std::vector<std::size_t> missing_at;
    {
      std::lock_guard<std::mutex> lock(state->mutex);
      for (std::size_t i = 0; i < candidates.size(); ++i) {
        const auto found = state->records.find(Key{k, candidates[i].first, relocalisation});
        if (found == state->records.end()) {
          missing.push_back(candidates[i]);
          missing_at.push_back(i);
        } else {
          out[i] = found->second;
          ++state->answered;
        }
      }
    }
    if (missing.empty()) return out;
    std::vector<LoopRegistration> made = inner ? inner(k, view_k, missing, relocalisation, pair, loop)
                                               : registerCandidates(k, view_k, missing, relocalisation, pair, loop);
    if (made.size() != missing.size())
      throw JobError("registration log: the registrar returned " + std::to_string(made.size()) + " registrations for " +
                  std::to_string(missing.size()) + " candidates");
    std::lock_guard<std::mutex> lock(state->mutex);
    std::string lines;
    for (std::size_t j = 0; j < made.size(); ++j) {
      const Key key{k, missing[j].first, relocalisation};
      // A registration that failed where it ran is not kept: a resumed job tries it again.
      if (made[j].attempt.reason.rfind(kRegistrationFailed, 0) != 0) {
        lines += recordLine(key, made[j]);
        if (state->records.emplace(key, made[j]).second) state->order.push_back(key);
      }
      out[missing_at[j]] = std::move(made[j]);
      ++state->registered;
    }
    state->append(lines);
    return out;
  };
}

std::size_t RegistrationLog::size() const {
  std::lock_guard<std::mutex> lock(state_->mutex);
  return state_->records.size();
}
std::size_t RegistrationLog::answered() const {
  std::lock_guard<std::mutex> lock(state_->mutex);
  return state_->answered;
}
std::size_t RegistrationLog::registered() const {
  std::lock_guard<std::mutex> lock(state_->mutex);
  return state_->registered;
}
const std::string& RegistrationLog::fingerprintHash() const { return state_->hash; }

}  // namespace gasp
