#include "gasp/graphslam/engine.h"

#include <fcntl.h>
#include <unistd.h>

#include <cstdio>
#include <iostream>

namespace gasp::graphslam {

namespace {

/// Standard input (fd 0) from /dev/null while it lives; restored after.
class StdinFromDevNull {
 public:
  StdinFromDevNull() {
    std::cout.flush();
    std::fflush(stdout);
    saved_ = ::dup(0);
    const int null_fd = ::open("/dev/null", O_RDONLY);
    if (null_fd >= 0) {
      ::dup2(null_fd, 0);
      ::close(null_fd);
    }
  }
  ~StdinFromDevNull() {
    if (saved_ >= 0) {
      ::dup2(saved_, 0);
      ::close(saved_);
    }
    std::clearerr(stdin);
    std::cin.clear();
  }
  StdinFromDevNull(const StdinFromDevNull&) = delete;
  StdinFromDevNull& operator=(const StdinFromDevNull&) = delete;

 private:
  int saved_ = -1;
};

}  // namespace

StdoutToStderr::StdoutToStderr() {
  std::cout.flush();
  std::fflush(stdout);
  saved_ = ::dup(1);
  if (saved_ >= 0) ::dup2(2, 1);
}

StdoutToStderr::~StdoutToStderr() {
  std::cout.flush();
  std::fflush(stdout);
  if (saved_ >= 0) {
    ::dup2(saved_, 1);
    ::close(saved_);
  }
}

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
