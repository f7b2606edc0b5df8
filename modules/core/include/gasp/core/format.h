#pragma once
/// \file format.h printf-style formatting into a std::string, for reasons and messages.
#include <cstdarg>
#include <cstdio>
#include <string>

namespace gasp {

/// std::vsnprintf into a string of the length needed; GCC and Clang check the conversions against
/// the arguments (-Wformat).
__attribute__((format(printf, 1, 2))) inline std::string formatted(const char* fmt, ...) {
  std::va_list args, copy;
  va_start(args, fmt);
  va_copy(copy, args);
  const int n = std::vsnprintf(nullptr, 0, fmt, copy);
  va_end(copy);
  std::string out;
  if (n > 0) {
    out.resize(static_cast<std::size_t>(n) + 1);
    std::vsnprintf(out.data(), out.size(), fmt, args);
    out.resize(static_cast<std::size_t>(n));
  }
  va_end(args);
  return out;
}

}  // namespace gasp
