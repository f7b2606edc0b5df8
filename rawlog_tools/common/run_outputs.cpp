#include "run_outputs.h"

#include <filesystem>
#include <stdexcept>

#include "gasp/core/error.h"
#include "gasp/core/tum_dataset.h"
#include "gasp/rawlog/rawlog_format.h"

namespace gasp::tools {

namespace fs = std::filesystem;

InputFiles::InputFiles(const std::vector<std::string>& paths) {
  for (const std::string& input : paths)
    if (const FileIdentity id = fileIdentity(input); id.exists()) ids_.emplace(id, input);
}

const std::string* InputFiles::find(const FileIdentity& id) const {
  if (!id.exists()) return nullptr;
  const auto it = ids_.find(id);
  return it == ids_.end() ? nullptr : &it->second;
}

RunOutputs::RunOutputs(const std::vector<std::pair<std::string, std::string>>& option_paths, const InputFiles& inputs) {

  for (const auto& [option, path] : option_paths) {
    if (path.empty()) continue;
    auto file = std::make_unique<OutputFile>(path, option);
    const FileIdentity id = fileIdentity(file->target());
    if (const std::string* input = inputs.find(id))
      throw Error(option + " '" + path + "': is an input of this run ('" + *input + "'); write it elsewhere");
    for (const auto& [other_option, other] : files_)
      if (other->target() == file->target() || (id.exists() && fileIdentity(other->target()) == id))
        throw Error(option + " '" + path + "': the same file as " + other_option + " '" + other->path() + "'");
    files_.emplace_back(option, std::move(file));
  }
}

OutputFile* RunOutputs::find(const std::string& option) {
  for (auto& [name, file] : files_)
    if (name == option) return file.get();
  return nullptr;
}

OutputFile& RunOutputs::at(const std::string& option, const std::string& path) {
  for (auto& [name, file] : files_)
    if (name == option && file->path() == path) return *file;
  throw std::logic_error("RunOutputs: no output " + option + " '" + path + "'");
}

OutputFile& RunOutputs::at(const std::string& option) {
  OutputFile* f = find(option);
  if (!f) throw std::logic_error("RunOutputs: no output " + option);
  return *f;
}

std::vector<std::string> tumFolderInputs(const std::string& dir) {
  if (dir.empty()) return {};
  std::vector<std::string> files;
  for (const char* name : {"depth.txt", "rgb.txt", "groundtruth.txt", "associations.txt", "intrinsics.txt"})
    files.push_back((fs::path(dir) / name).string());
  for (const char* list : {"depth.txt", "rgb.txt"}) {
    const fs::path list_path = fs::path(dir) / list;
    std::error_code ec;
    if (!fs::is_regular_file(list_path, ec)) continue;
    try {
      for (const auto& [stamp, name] : readTumFileList(list_path.string())) {
        static_cast<void>(stamp);
        files.push_back(fs::path(name).is_absolute() ? name : (fs::path(dir) / name).string());
      }
    } catch (const Error&) {
      // the folder's reader reports it
    }
  }
  return files;
}

std::vector<std::string> rawlogInputs(const std::string& rawlog_path) {
  if (rawlog_path.empty()) return {};
  std::vector<std::string> files{rawlog_path};
  std::error_code ec;
  const std::string images = findRawlogImagesDirectory(rawlog_path);
  if (images.empty() || !fs::is_directory(images, ec)) return files;
  for (fs::recursive_directory_iterator it(images, ec), end; !ec && it != end; it.increment(ec))
    if (it->is_regular_file(ec)) files.push_back(it->path().string());
  return files;
}

std::vector<std::string> intrinsicsFileInput(const std::string& intrinsics) {
  std::error_code ec;
  if (intrinsics.empty() || !fs::is_regular_file(intrinsics, ec)) return {};
  return {intrinsics};
}

}  // namespace gasp::tools
