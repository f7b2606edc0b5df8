#pragma once
// Test helpers: run one of GASP's programs (from the build's bin folder) and capture its exit code
// and output (stdout and stderr); look into that output and the files it wrote.
#include <sys/wait.h>

#include <array>
#include <cstddef>
#include <cstdio>
#include <fstream>
#include <memory>
#include <string>

namespace gasp::test {

struct ProgramRun {
  int exit_code;
  std::string output;  ///< stdout and stderr
};

/// Runs a shell command line and captures its stdout.
inline ProgramRun runCommand(const std::string& cmd) {
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(cmd.c_str(), "r"), pclose);
  if (!pipe) return {-1, "cannot start " + cmd};
  std::string out;
  std::array<char, 4096> buf{};
  while (std::fgets(buf.data(), static_cast<int>(buf.size()), pipe.get())) out += buf.data();
  const int status = pclose(pipe.release());
  return {WEXITSTATUS(status), out};
}

/// Runs the program; `stderr_to` is where its stderr goes ("&1": into `output` with stdout);
/// `cwd`, when given, is its working folder (for outputs whose default path is relative).
inline ProgramRun runProgram(const std::string& program, const std::string& args, const std::string& stderr_to = "&1",
                             const std::string& cwd = "") {
  return runCommand((cwd.empty() ? std::string() : "cd '" + cwd + "' && ") + std::string(GASP_BIN_DIR) + "/" + program +
                    " " + args + " 2>" + stderr_to);
}

/// `part` occurs in `s` (a program's output).
inline bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

/// Lines of the file at `path` that start with `prefix` (0 when it cannot be read).
inline std::size_t countLinesStartingWith(const std::string& path, const std::string& prefix) {
  std::ifstream in(path);
  std::size_t n = 0;
  for (std::string line; std::getline(in, line);) n += line.rfind(prefix, 0) == 0 ? 1 : 0;
  return n;
}

/// The count printed after `key` in a program's output (SIZE_MAX when the key is absent).
inline std::size_t printedCount(const std::string& output, const std::string& key) {
  const auto pos = output.find(key);
  return pos == std::string::npos ? static_cast<std::size_t>(-1) : std::stoul(output.substr(pos + key.size()));
}

}  // namespace gasp::test
