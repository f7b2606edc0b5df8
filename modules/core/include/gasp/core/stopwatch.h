#pragma once
/// \file stopwatch.h Wall time in milliseconds, for the per-stage times the result structs report.
#include <chrono>

namespace gasp {

/// Milliseconds of wall time (steady clock) since t0.
inline double msSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace gasp
