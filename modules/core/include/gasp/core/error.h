#pragma once
/// \file error.h The one exception type GASP throws for bad input and I/O failures.
#include <stdexcept>
#include <string>

namespace gasp {

/// Thrown for missing or corrupt files, malformed lines and invalid arguments. The message
/// names the file (and line or field) and says what was expected.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace gasp
