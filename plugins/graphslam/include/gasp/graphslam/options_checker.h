#pragma once
/// \file options_checker.h The one place where GASP's mrpt::graphslam classes are registered:
/// an mrpt::graphslam::apps::TUserOptionsChecker for 3D graphs that knows CGaspOdometryNRD,
/// CGaspLoopClosureERD and CGaspPoseGraphGSO beside MRPT's own deciders and optimisers (MRPT 2.5.8
/// has no 3D node or edge registration decider of its own besides CFixedIntervalsNRD and the
/// empty ones). graphslam-engine has no plugin option, so gasp-graphslam uses this checker.
// MRPT 2.5.8's TUserOptionsChecker.h compiles only after these (its deciders' sources use
// CConfigFile and an unqualified endl, which the engine's headers bring in).
#include <mrpt/config/CConfigFile.h>
#include <mrpt/graphslam/CGraphSlamEngine.h>

#include <iostream>

#include <mrpt/graphslam/apps_related/TUserOptionsChecker.h>

#include "gasp/graphslam/graph_types.h"

namespace gasp::graphslam {

class GaspOptionsChecker : public mrpt::graphslam::apps::TUserOptionsChecker<Graph3D> {
 public:
  /// Fills the maps and the descriptions (no need to call the two methods below).
  GaspOptionsChecker();
  void _createDeciderOptimizerMappings() override;
  void populateDeciderOptimizerProperties() override;
};

}  // namespace gasp::graphslam
