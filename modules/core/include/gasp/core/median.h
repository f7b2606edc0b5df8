#pragma once
/// \file median.h The median of a sample, as every stage that needs a robust centre takes it.
#include <algorithm>
#include <cstddef>
#include <vector>

namespace gasp {

/// The median of v: the upper of the two middle values for an even count; 0 for an empty v.
inline double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

}  // namespace gasp
