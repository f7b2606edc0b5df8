#pragma once
/// \file engine.h mrpt::graphslam::CGraphSlamEngine for 3D graphs, made to run unattended.
#include <mrpt/graphslam/CGraphSlamEngine.h>

#include <memory>
#include <string>

#include "gasp/graphslam/graph_types.h"

namespace gasp::graphslam {

using GraphSlamEngine = mrpt::graphslam::CGraphSlamEngine<Graph3D>;

/// The engine without a window, reading `ini` (its [GeneralConfiguration] and
/// [VisualizationParameters], and each decider's and the optimiser's sections). The deciders and
/// the optimiser stay the caller's (the engine does not delete them) and must outlive it.
///
/// MRPT 2.5.8's constructor waits for a key press (mrpt::system::pause()) for every graph type:
/// it compares the constraint's class name, which carries its namespace
/// ("mrpt::poses::CPose3DPDFGaussianInf"), with names that do not, and warns that the class is
/// untested. This function gives that pause /dev/null as its standard input, so it returns at
/// once whatever the process's standard input is. Throws what the constructor throws (e.g. for
/// an invalid key in a section).
/// Standard output goes to standard error while it lives (flushed on both sides). MRPT's engine,
/// deciders and optimisers log to standard output (class messages, warnings, the time logger's
/// table when the engine is destroyed); a program whose standard output is its result holds one
/// of these from before the deciders are made until the engine is gone.
class StdoutToStderr {
 public:
  StdoutToStderr();
  ~StdoutToStderr();
  StdoutToStderr(const StdoutToStderr&) = delete;
  StdoutToStderr& operator=(const StdoutToStderr&) = delete;

 private:
  int saved_ = -1;
};

std::unique_ptr<GraphSlamEngine> makeGraphSlamEngine(
    const std::string& ini, const std::string& rawlog,
    mrpt::graphslam::deciders::CNodeRegistrationDecider<Graph3D>& node_registration,
    mrpt::graphslam::deciders::CEdgeRegistrationDecider<Graph3D>& edge_registration,
    mrpt::graphslam::optimizers::CGraphSlamOptimizer<Graph3D>& optimizer);

}  // namespace gasp::graphslam
