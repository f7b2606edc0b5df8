#pragma once
/// \file params_options.h --params FILE and --print-params, the same in every program.
///
/// The values a program runs with are its defaults, then the params file's (--params), then its
/// own command-line options: the file is loaded before CLI11 binds the options, so the options
/// show the file's values as their defaults and a given option overrides the file.
/// --print-params writes the effective values as a params file to stdout and exits 0, without
/// needing the program's inputs: `PROGRAM [options] --print-params > my.yaml` gives a file that
/// `--params my.yaml` loads back to the same values.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <cstring>
#include <iostream>
#include <string>

#include "gasp/core/error.h"
#include "gasp/params/params_file.h"

namespace gasp::tools {

class ParamsOptions {
 public:
  /// Reads the --params FILE given on the command line (`--params FILE` or `--params=FILE`) into
  /// `params`. False after printing "error: params 'FILE' line N: ..." (the program exits 1).
  bool preload(int argc, char** argv, SlamParams& params) {
    for (int i = 1; i < argc; ++i) {
      const char* arg = argv[i];
      if (std::strcmp(arg, "--") == 0) break;
      if (std::strcmp(arg, "--params") == 0 && i + 1 < argc) {
        file_ = argv[i + 1];
      } else if (std::strncmp(arg, "--params=", 9) == 0) {
        file_ = arg + 9;
      } else if (std::strcmp(arg, "--print-params") == 0) {
        print_requested_ = true;
      }
    }
    if (file_.empty()) return true;
    try {
      params = readParamsFile(file_, params);
    } catch (const Error& e) {
      std::cerr << "error: " << e.what() << '\n';
      return false;
    }
    return true;
  }

  /// Registers --params and --print-params (after preload()).
  void add(CLI::App& app) {
    app.add_option("--params", file_,
                   "a params file (YAML, docs/parameters.md): its values replace the defaults, and the options given "
                   "here replace the file's");
    app.add_flag("--print-params", print_,
                 "print the parameters this run would use, as a params file, and exit (no input needed)");
  }

  /// -1 without --print-params (the program goes on); with it, prints `params` (the effective
  /// values) and returns the exit code: 0, or 1 when stdout could not be written.
  int printIfAsked(const SlamParams& params) const {
    if (!print_) return -1;
    std::cout << "# GASP parameters (docs/parameters.md): load with --params FILE\n" << paramsYaml(params);
    std::cout.flush();
    if (!std::cout) {
      std::cerr << "error: cannot write the parameters to stdout\n";
      return 1;
    }
    return 0;
  }

  /// For a program none of whose options sets a parameter (it reads the file only to check it):
  /// --print-params prints the file's values before the command line is parsed, so that the
  /// program's required arguments are not needed. The same return values as printIfAsked().
  int printBeforeParse(const SlamParams& params) {
    print_ = print_requested_;
    return printIfAsked(params);
  }

  const std::string& file() const { return file_; }
  bool printing() const { return print_; }

 private:
  std::string file_;
  bool print_ = false;
  bool print_requested_ = false;  ///< --print-params seen by preload()
};

/// -1 when the parameters, with the command-line options applied, are valid; else prints
/// "error: ..." and returns 2 (an option's value the file's others do not allow).
inline int validOptionValues(const SlamParams& params) {
  try {
    validate(params);
  } catch (const Error& e) {
    std::cerr << "error: " << e.what() << "\nRun with --help for more information.\n";
    return 2;
  }
  return -1;
}

}  // namespace gasp::tools
