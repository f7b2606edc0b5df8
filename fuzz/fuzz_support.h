#pragma once
/// \file fuzz_support.h (fuzz targets only) The input written to a file of this process for
/// readers that take a path, and the expected outcome of bad input: a gasp::Error (or another
/// std::exception, which the programs also report as a one-line error). Anything else -- a crash,
/// an abort, a sanitizer report, a hang, a huge allocation -- ends the process and is a finding.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <typeinfo>

#include "gasp/core/error.h"

namespace gasp::fuzz {

/// Scratch folder of this process: $GASP_FUZZ_TMP, else /dev/shm (no disk writes), else /tmp.
inline std::string scratchRoot() {
  if (const char* env = std::getenv("GASP_FUZZ_TMP"); env && *env) return env;
  std::error_code ec;
  if (std::filesystem::is_directory("/dev/shm", ec)) return "/dev/shm";
  return "/tmp";
}

/// A folder of its own for this process (libFuzzer's -jobs/-workers run several), removed at exit.
class ScratchDir {
 public:
  explicit ScratchDir(const std::string& name)
      : path_(scratchRoot() + "/gasp_fuzz_" + name + "_" + std::to_string(::getpid())) {
    std::filesystem::create_directories(path_);
  }
  ~ScratchDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  const std::string& path() const { return path_; }
  /// Writes `size` bytes to the file `name` in the folder (replacing it); returns its path.
  std::string write(const std::string& name, const void* data, std::size_t size) const {
    const std::string file = path_ + "/" + name;
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out.write(static_cast<const char*>(data), static_cast<std::streamsize>(size));
    out.close();
    if (!out) {
      std::fprintf(stderr, "fuzz harness: cannot write %s\n", file.c_str());
      std::abort();  // the harness's fault, not the reader's: stop rather than fuzz nothing
    }
    return file;
  }

 private:
  std::string path_;
};

/// A std::exception that is not a gasp::Error: expected, but printed the first time each type is
/// seen (the documented readers throw gasp::Error; the log shows what else leaks through).
/// GASP_FUZZ_STRICT=1 makes it a finding (abort).
inline void otherException(const std::exception& e) {
  static std::set<std::string> seen;
  static const bool strict = [] {
    const char* env = std::getenv("GASP_FUZZ_STRICT");
    return env && std::string(env) == "1";
  }();
  const std::string type = typeid(e).name();
  if (strict || seen.insert(type).second)
    std::fprintf(stderr, "fuzz harness: %s (not gasp::Error): %.300s\n", type.c_str(), e.what());
  if (strict) std::abort();
}

/// GASP_FUZZ_VERBOSE=1: every error message printed (to see why a crash input is rejected).
inline bool verbose() {
  static const bool on = [] {
    const char* env = std::getenv("GASP_FUZZ_VERBOSE");
    return env && std::string(env) == "1";
  }();
  return on;
}

/// Runs f(); gasp::Error and other std::exceptions are the expected ends of bad input.
template <class F>
void expectErrorsOnly(F&& f) {
  try {
    f();
    if (verbose()) std::fprintf(stderr, "fuzz harness: read without error\n");
  } catch (const gasp::Error& e) {
    if (verbose()) std::fprintf(stderr, "fuzz harness: gasp::Error: %s\n", e.what());
  } catch (const std::exception& e) {
    otherException(e);
  }
}

}  // namespace gasp::fuzz
