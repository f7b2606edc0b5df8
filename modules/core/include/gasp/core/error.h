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

/// `text` safe to print on a terminal: control characters (newlines included) and bytes that are
/// not part of valid UTF-8 become "\xNN", so that a message quoting a line of a binary file stays
/// one readable line; valid UTF-8 (file names with accents) is kept.
inline std::string printable(const std::string& text) {
  static const char hex[] = "0123456789abcdef";
  std::string out;
  out.reserve(text.size());
  const auto escape = [&out](unsigned char c) {
    out += "\\x";
    out += hex[c >> 4];
    out += hex[c & 15];
  };
  for (std::size_t i = 0; i < text.size();) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c < 0x20 || c == 0x7f) {
      escape(c);
      ++i;
      continue;
    }
    if (c < 0x80) {
      out += static_cast<char>(c);
      ++i;
      continue;
    }
    // A UTF-8 sequence: its length from the lead byte, continuation bytes 10xxxxxx, no overlong
    // two-byte forms (0xc0, 0xc1) and nothing beyond U+10FFFF (lead bytes above 0xf4).
    const std::size_t length = c >= 0xc2 && c <= 0xdf ? 2 : c >= 0xe0 && c <= 0xef ? 3 : c >= 0xf0 && c <= 0xf4 ? 4 : 0;
    bool valid = length > 0 && i + length <= text.size();
    for (std::size_t k = 1; valid && k < length; ++k) valid = (static_cast<unsigned char>(text[i + k]) & 0xc0) == 0x80;
    if (!valid) {
      escape(c);
      ++i;
      continue;
    }
    out.append(text, i, length);
    i += length;
  }
  return out;
}

/// An exception's message in one printable line (printable()): MRPT's exceptions carry a banner
/// ("==== MRPT exception ====") and a stack trace, of which only the "Message:" line is kept;
/// others are as they are.
inline std::string exceptionMessage(const std::exception& e) {
  const std::string what = e.what();
  const auto m = what.find("Message:");
  if (m == std::string::npos) return printable(what);
  auto begin = what.find_first_not_of(' ', m + 8);
  if (begin == std::string::npos) begin = m + 8;
  return printable(what.substr(begin, what.find('\n', begin) - begin));
}

}  // namespace gasp
