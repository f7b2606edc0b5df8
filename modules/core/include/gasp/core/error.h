#pragma once
/// \file error.h The one exception type GASP throws for bad input and I/O failures.
#include <cmath>
#include <exception>
#include <stdexcept>
#include <string>

namespace gasp {

/// Thrown for missing or corrupt files, malformed lines and invalid arguments. The message
/// names the file (and line or field) and says what was expected.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Throws Error("<name> must be positive and finite") unless v is (NaN fails too), for the
/// parameter validators; `name` says whose parameter it is (e.g. "odometry: max_speed_mps").
inline void requirePositive(double v, const std::string& name) {
  if (!(v > 0.0) || !std::isfinite(v)) throw Error(name + " must be positive and finite");
}

/// An exception's message in one line: MRPT's exceptions carry a banner ("==== MRPT exception
/// ====") and a stack trace, of which only the "Message:" line is kept; others are as they are.
inline std::string exceptionMessage(const std::exception& e) {
  const std::string what = e.what();
  const auto m = what.find("Message:");
  if (m == std::string::npos) return what;
  auto begin = what.find_first_not_of(' ', m + 8);
  if (begin == std::string::npos) begin = m + 8;
  return what.substr(begin, what.find('\n', begin) - begin);
}

}  // namespace gasp
