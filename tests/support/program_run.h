#pragma once
// Test helper: run one of GASP's programs (from the build's bin folder) and capture its exit code
// and output (stdout and stderr).
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <memory>
#include <string>

namespace gasp::test {

struct ProgramRun {
  int exit_code;
  std::string output;  ///< stdout and stderr
};

inline ProgramRun runProgram(const std::string& program, const std::string& args) {
  const std::string cmd = std::string(GASP_BIN_DIR) + "/" + program + " " + args + " 2>&1";
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(cmd.c_str(), "r"), pclose);
  if (!pipe) return {-1, "cannot start " + cmd};
  std::string out;
  std::array<char, 4096> buf{};
  while (std::fgets(buf.data(), static_cast<int>(buf.size()), pipe.get())) out += buf.data();
  const int status = pclose(pipe.release());
  return {WEXITSTATUS(status), out};
}

}  // namespace gasp::test
