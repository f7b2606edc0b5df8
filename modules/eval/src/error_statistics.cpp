#include "gasp/eval/error_statistics.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace gasp::eval {

ErrorStatistics computeStatistics(std::vector<double> errors) {
  ErrorStatistics s;
  s.count = errors.size();
  if (errors.empty()) return s;
  std::sort(errors.begin(), errors.end());
  const double n = static_cast<double>(errors.size());
  s.mean = std::accumulate(errors.begin(), errors.end(), 0.0) / n;
  double sq = 0.0, var = 0.0;
  for (double e : errors) {
    sq += e * e;
    var += (e - s.mean) * (e - s.mean);
  }
  s.rmse = std::sqrt(sq / n);
  s.std = std::sqrt(var / n);
  const std::size_t mid = errors.size() / 2;
  s.median = errors.size() % 2 ? errors[mid] : 0.5 * (errors[mid - 1] + errors[mid]);
  s.min = errors.front();
  s.max = errors.back();
  return s;
}

}  // namespace gasp::eval
