#pragma once
/// \file pairs_csv.h gasp-pairs --pairs-csv: one line per pair and method (the columns are listed
/// in docs/evaluation.md). Empty fields where a value does not exist (no estimate, no ground
/// truth, no GICP, no rgb).
#include <optional>
#include <string>

#include "gasp/core/pose.h"
#include "gasp/eval/pair_protocol.h"
#include "method_run.h"
#include "rgb_check.h"

namespace gasp::pairs {

/// The header line (no newline).
std::string pairsCsvHeader();

/// What a line holds beside the run: the reference and the optional checks.
struct PairsCsvChecks {
  Isometry3 T_gt = Isometry3::Identity();  ///< the reference T_target_source (its motion columns)
  std::optional<Isometry3> T_ref_icp;      ///< --polish-reference: GICP from the reference
  std::optional<Isometry3> T_est_icp;      ///< --polish-reference: GICP from the estimate
  RgbCheck rgb;                            ///< --rgb-rotation-check
};

/// One line (no newline) with as many fields as the header.
std::string pairsCsvRow(const eval::PairOutcome& o, const std::string& method, const MethodRun& run,
                        const PairsCsvChecks& checks);

}  // namespace gasp::pairs
