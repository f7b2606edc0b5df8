#include "gasp/rawlog/rawlog_format.h"

#include <filesystem>

#include "gasp/core/error.h"

namespace gasp {

RawlogFormat rawlogFormatFromNumber(int number) {
  if (number == 1) return RawlogFormat::ActionsSensoryFrames;
  if (number == 2) return RawlogFormat::Observations;
  throw Error("rawlog format must be 1 (actions + sensory frames) or 2 (observations), got " +
              std::to_string(number));
}

std::string rawlogImagesDirectory(const std::string& rawlog_path) {
  const std::filesystem::path p(rawlog_path);
  return (p.parent_path() / (p.stem().string() + "_Images")).string();
}

std::string findRawlogImagesDirectory(const std::string& rawlog_path) {
  const std::filesystem::path p(rawlog_path);
  std::error_code ec;
  for (const char* suffix : {"_Images", "_images", "_IMAGES"}) {
    const auto dir = p.parent_path() / (p.stem().string() + suffix);
    if (std::filesystem::is_directory(dir, ec)) return dir.string();
  }
  return (p.parent_path() / "Images").string();
}

}  // namespace gasp
