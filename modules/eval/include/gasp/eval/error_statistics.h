#pragma once
/// \file error_statistics.h Summary statistics of a list of errors, as TUM's evaluation scripts
/// print them (numpy definitions: population standard deviation, median of the middle two).
#include <cstddef>
#include <vector>

namespace gasp::eval {

struct ErrorStatistics {
  std::size_t count = 0;
  double rmse = 0.0;
  double mean = 0.0;
  double median = 0.0;
  double std = 0.0;  ///< population standard deviation (numpy.std)
  double min = 0.0;
  double max = 0.0;
};

/// Statistics of `errors`; all zero with count 0 for an empty list.
ErrorStatistics computeStatistics(std::vector<double> errors);

}  // namespace gasp::eval
