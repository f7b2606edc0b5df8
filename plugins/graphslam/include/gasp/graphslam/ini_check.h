#pragma once
/// \file ini_check.h What MRPT's CConfigFile passes over silently in a graph-SLAM configuration:
/// lines that are neither a [section] nor `key = value` (a typo, or not an ini file at all), and
/// sections no decider reads (a misspelt section name leaves its keys unread).
#include <string>
#include <vector>

namespace gasp::graphslam {

struct IniCheck {
  std::string error;  ///< the first malformed line ("FILE:LINE: ..."), empty when none
  /// Sections read by neither GASP's deciders nor MRPT's engine and deciders, in file order.
  std::vector<std::string> unknown_sections;
};

/// Reads `path` (throws gasp::Error when it cannot be opened). Blank lines and comments (`#`,
/// `;`, `//`) are fine. Known sections: GeneralConfiguration, VisualizationParameters,
/// NodeRegistrationDeciderParameters, EdgeRegistrationDeciderParameters, OptimizerParameters
/// (MRPT's), CGaspOdometryNRD, CGaspLoopClosureERD, CGaspPoseGraphGSO (GASP's).
IniCheck checkGraphSlamIni(const std::string& path);

}  // namespace gasp::graphslam
