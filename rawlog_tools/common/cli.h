#pragma once
/// \file cli.h What every GASP program does with its command line: exit codes (0 for --help, 2
/// for any usage error, whatever CLI11's own code) and validators with plain messages.
#include <CLI/CLI.hpp>

#include "run_outputs.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>


namespace gasp::tools {

/// Parses the command line. Returns -1 when the program should go on, else its exit code: 0
/// after --help (CLI11 prints it), 2 after a usage error ("error: MESSAGE" on stderr, as every
/// other error of the programs).
/// The exit code for a CLI11 parse error: 0 after --help (printed), else 2 with "error: MESSAGE".
inline int usageExit(CLI::App& app, const CLI::ParseError& e) {
  if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) return app.exit(e) == 0 ? 0 : 2;
  std::fprintf(stderr, "error: %s\nRun with --help for more information.\n", e.what());
  return 2;
}

inline int parseCommandLine(CLI::App& app, int argc, char** argv) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return usageExit(app, e);
  }
  return -1;
}

namespace detail {
inline std::string shortNumber(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}
/// The option's value as a finite number, or "" with `error` set.
inline bool finiteValue(const std::string& text, double& v, std::string& error) {
  try {
    std::size_t used = 0;
    v = std::stod(text, &used);
    if (used != text.size()) throw std::invalid_argument(text);
  } catch (const std::exception&) {
    error = "not a number: '" + text + "'";
    return false;
  }
  if (!std::isfinite(v)) {
    error = "must be a finite number (got " + text + ")";
    return false;
  }
  // An integer beyond what a 64-bit option holds: CLI11 would clamp or wrap it. (Not for numbers
  // written with a point or an exponent: such a text is no integer, and CLI11 refuses it for an
  // integer option.)
  if (text.find_first_not_of("+-0123456789") == std::string::npos && std::fabs(v) >= 9.2e18) {
    error = "is too large (got " + text + ")";
    return false;
  }
  return true;
}
}  // namespace detail

namespace detail {
/// A validator of finite numbers: `problem(v, text)` says what is wrong with v, or "".
template <class Problem>
CLI::Validator numberValidator(const std::string& description, Problem problem) {
  return CLI::Validator(
      [problem](std::string& text) -> std::string {
        double v = 0;
        std::string error;
        if (!finiteValue(text, v, error)) return error;
        return problem(v, text);
      },
      description);
}
}  // namespace detail

/// A finite number >= lo ("must be at least 1 (got 0)"). On unsigned options, `atLeast(0)` keeps
/// CLI11 from wrapping "-1" round to 18446744073709551615.
inline CLI::Validator atLeast(double lo) {
  return detail::numberValidator(">= " + detail::shortNumber(lo), [lo](double v, const std::string& text) {
    return v < lo ? "must be at least " + detail::shortNumber(lo) + " (got " + text + ")" : std::string();
  });
}

/// A finite number > lo.
inline CLI::Validator above(double lo) {
  return detail::numberValidator("> " + detail::shortNumber(lo), [lo](double v, const std::string& text) {
    return !(v > lo) ? "must be greater than " + detail::shortNumber(lo) + " (got " + text + ")" : std::string();
  });
}

/// A finite number in [lo, hi].
inline CLI::Validator within(double lo, double hi) {
  return detail::numberValidator(
      "in [" + detail::shortNumber(lo) + ", " + detail::shortNumber(hi) + "]", [lo, hi](double v, const std::string& text) {
        return v < lo || v > hi ? "must be between " + detail::shortNumber(lo) + " and " + detail::shortNumber(hi) +
                                      " (got " + text + ")"
                                : std::string();
      });
}

/// A finite number in (lo, hi].
inline CLI::Validator aboveAndAtMost(double lo, double hi) {
  return detail::numberValidator(
      "in (" + detail::shortNumber(lo) + ", " + detail::shortNumber(hi) + "]", [lo, hi](double v, const std::string& text) {
        return !(v > lo) || v > hi ? "must be greater than " + detail::shortNumber(lo) + " and at most " +
                                         detail::shortNumber(hi) + " (got " + text + ")"
                                   : std::string();
      });
}

/// 0 (off) or a finite number in [lo, hi).
inline CLI::Validator zeroOrWithinHalfOpen(double lo, double hi) {
  return detail::numberValidator(
      "0 or in [" + detail::shortNumber(lo) + ", " + detail::shortNumber(hi) + ")",
      [lo, hi](double v, const std::string& text) {
        return v == 0.0 || (v >= lo && v < hi) ? std::string()
                                               : "must be 0 (off) or at least " + detail::shortNumber(lo) + " and below " +
                                                     detail::shortNumber(hi) + " (got " + text + ")";
      });
}

/// 0 (off) or a finite number >= lo.
inline CLI::Validator zeroOrAtLeast(double lo) {
  return detail::numberValidator("0 or >= " + detail::shortNumber(lo), [lo](double v, const std::string& text) {
    return v == 0.0 || v >= lo ? std::string()
                               : "must be 0 (off) or at least " + detail::shortNumber(lo) + " (got " + text + ")";
  });
}

/// A non-empty value (a file name given as "" would silently write nothing).
inline CLI::Validator nonEmpty() {
  return CLI::Validator([](std::string& text) -> std::string { return text.empty() ? "must not be empty" : ""; },
                        "non-empty");
}

/// Any finite number (NaN and infinities refused).
inline CLI::Validator finite() {
  return detail::numberValidator("finite", [](double, const std::string&) { return std::string(); });
}

/// The "intrinsics: SUMMARY" line of a program that reads a TUM folder (on `out`: stdout, or
/// stderr where stdout is a table) and, when its camera was only guessed, the warning on stderr.
inline void reportIntrinsics(std::FILE* out, const std::string& summary, const std::string& warning) {
  std::fprintf(out, "intrinsics: %s\n", summary.c_str());
  if (!warning.empty()) std::fprintf(stderr, "warning: %s\n", warning.c_str());
}

}  // namespace gasp::tools
