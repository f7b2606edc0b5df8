#include "gasp/graphslam/engine.h"

#include <fcntl.h>
#include <unistd.h>

#include <cstdio>
#include <iostream>

namespace gasp::graphslam {

namespace {

/// Points `fd` at `target` (both flushed first); returns a copy of the old `fd` for restoreFd(),
/// or -1 when it could not be saved (then nothing changes).
int redirectFd(int fd, int target) {
  std::cout.flush();
  std::fflush(stdout);
  const int saved = ::dup(fd);
  if (saved >= 0) ::dup2(target, fd);
  return saved;
}

void restoreFd(int fd, int saved) {
  std::cout.flush();
  std::fflush(stdout);
  if (saved < 0) return;
  ::dup2(saved, fd);
  ::close(saved);
}

/// Standard input (fd 0) from /dev/null while it lives; restored after.
class StdinFromDevNull {
 public:
  StdinFromDevNull() {
    const int null_fd = ::open("/dev/null", O_RDONLY);
    if (null_fd < 0) return;
    saved_ = redirectFd(0, null_fd);
    ::close(null_fd);
  }
  ~StdinFromDevNull() {
    restoreFd(0, saved_);
    std::clearerr(stdin);
    std::cin.clear();
  }
  StdinFromDevNull(const StdinFromDevNull&) = delete;
  StdinFromDevNull& operator=(const StdinFromDevNull&) = delete;

 private:
  int saved_ = -1;
};

}  // namespace

StdoutToStderr::StdoutToStderr() : saved_(redirectFd(1, 2)) {}

StdoutToStderr::~StdoutToStderr() { restoreFd(1, saved_); }

std::unique_ptr<GraphSlamEngine> makeGraphSlamEngine(
    const std::string& ini, const std::string& rawlog,
    mrpt::graphslam::deciders::CNodeRegistrationDecider<Graph3D>& node_registration,
    mrpt::graphslam::deciders::CEdgeRegistrationDecider<Graph3D>& edge_registration,
    mrpt::graphslam::optimizers::CGraphSlamOptimizer<Graph3D>& optimizer) {
  const StdinFromDevNull no_key_press;
  return std::make_unique<GraphSlamEngine>(ini, rawlog, "", nullptr, &node_registration, &edge_registration,
                                           &optimizer);
}

}  // namespace gasp::graphslam
