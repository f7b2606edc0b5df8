#pragma once
/// \file run_outputs.h The output files of one program run, opened before the work.
///
/// Every program names its outputs (option and path) and its inputs; RunOutputs then, before any
/// work: refuses an output that is an input of the run (compared by file identity, so symbolic
/// and hard links are seen through) or the same file as another output, and opens each output
/// (gasp/core/output_file.h: a device, FIFO or folder is refused, a folder that cannot be written
/// fails now, not after an hour of work). Each output is then written to its stream and published
/// whole by commit(); an output never committed leaves its target as it was.
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "gasp/core/output_file.h"

namespace gasp::tools {

/// The files a run reads, by identity (device and inode: symbolic and hard links seen through).
class InputFiles {
 public:
  explicit InputFiles(const std::vector<std::string>& paths);
  /// The input that `id` is, or nullptr.
  const std::string* find(const FileIdentity& id) const;

 private:
  std::map<FileIdentity, std::string> ids_;
};

class RunOutputs {
 public:
  /// Opens the outputs {option, path} (empty paths: option not given) after the checks above;
  /// throws gasp::Error naming the option and path ("--out 'x': is an input of this run ('y')").
  RunOutputs(const std::vector<std::pair<std::string, std::string>>& option_paths, const InputFiles& inputs);
  RunOutputs(const std::vector<std::pair<std::string, std::string>>& option_paths, const std::vector<std::string>& inputs)
      : RunOutputs(option_paths, InputFiles(inputs)) {}

  /// The (first) output of `option`, or nullptr when it was not given.
  OutputFile* find(const std::string& option);
  /// The output of `option`; throws std::logic_error when it was not given.
  OutputFile& at(const std::string& option);
  /// The output of an option that names several files (gasp-pairs' --picture-prefix, one picture
  /// per method), by its path; throws std::logic_error when there is none.
  OutputFile& at(const std::string& option, const std::string& path);

 private:
  std::vector<std::pair<std::string, std::unique_ptr<OutputFile>>> files_;  ///< in the order given
};

/// The files a TUM folder's reader takes as input: its lists (depth.txt, rgb.txt,
/// groundtruth.txt, associations.txt, intrinsics.txt) and every image depth.txt and rgb.txt
/// name; none when `dir` is empty. Lists that cannot be read add nothing (the reader reports
/// them).
std::vector<std::string> tumFolderInputs(const std::string& dir);

/// A rawlog and the files of its external images folder ("<name>_Images").
std::vector<std::string> rawlogInputs(const std::string& rawlog_path);

/// `--intrinsics` as an input file: none when it is empty or a preset name such as fr1 (a file of
/// that name is read only where it is not a preset).
std::vector<std::string> intrinsicsFileInput(const std::string& intrinsics);

}  // namespace gasp::tools
