#pragma once
/// \file pairs_table.h gasp-pairs' printed table: one row per skip and method (pair_protocol.h),
/// then each method's median time per stage.
#include <cstddef>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "gasp/eval/pair_protocol.h"

namespace gasp::pairs {

struct PairsTally {
  std::map<std::string, std::vector<eval::PairOutcome>> by_method;
  std::map<std::string, std::map<std::string, std::vector<double>>> stage_ms;  ///< method -> stage -> ms
  std::map<std::pair<std::size_t, std::string>, std::size_t> no_rgb;  ///< (skip, method) -> pairs left out
  std::map<std::size_t, std::size_t> pairs_per_skip;
};

/// Prints the table to stdout; returns the rows with scored pairs (for --csv) and, in
/// `total_pairs`, the pairs scored over all rows.
std::vector<eval::SkipSummary> printPairsTable(const std::vector<std::size_t>& skips,
                                               const std::vector<std::string>& methods, const PairsTally& tally,
                                               std::size_t& total_pairs);

/// Prints "median_ms_per_stage METHOD: STAGE MS ..." per method that has stage times.
void printStageTimes(const std::vector<std::string>& methods, const PairsTally& tally);

/// The median (0 for none; error_statistics.h's definition).
double median(std::vector<double> v);

}  // namespace gasp::pairs
