#include "gasp/core/image_file.h"

#include <opencv2/imgcodecs.hpp>

#include <filesystem>
#include <fstream>
#include <string_view>
#include <vector>

#include "gasp/core/error.h"
#include "image_header.h"

namespace gasp {

namespace {

/// The first line of an OpenCV exception's message (its `err`, without file and line).
std::string openCvMessage(const cv::Exception& e) { return e.err.empty() ? e.what() : e.err; }

}  // namespace

void requireImageWriter(const std::string& path, const std::string& what) {
  bool ok = false;
  try {
    ok = !path.empty() && cv::haveImageWriter(path);
  } catch (const cv::Exception&) {
    ok = false;
  }
  if (!ok)
    throw Error(what + " '" + path + "': no image format for this file name; use .png, .jpg, .bmp, .tif or .ppm");
}

void writeImage(OutputFile& out, const cv::Mat& image, const std::string& what) {
  const std::string& path = out.path();
  requireImageWriter(path, what);
  std::vector<uchar> bytes;
  bool ok = false;
  try {
    ok = cv::imencode(std::filesystem::path(path).extension().string(), image, bytes);
  } catch (const cv::Exception& e) {
    throw Error("cannot write " + what + " '" + path + "': " + openCvMessage(e));
  }
  if (!ok) throw Error("cannot write " + what + " '" + path + "': the image cannot be encoded in this format");
  out.write(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
  out.commit();
}

void writeImage(const std::string& path, const cv::Mat& image, const std::string& what) {
  requireImageWriter(path, what);
  OutputFile out(path, what);
  writeImage(out, image, what);
}

cv::Mat readImage(const std::string& path, int flags, const std::string& what) {
  if (!std::ifstream(path).good()) throw Error(what + " '" + path + "' cannot be opened");
  // OpenCV allocates the image its header declares before decoding: checked against the file first.
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (const std::string problem = ec ? "" : detail::imageHeaderProblem(path, size); !problem.empty())
    throw Error(what + " '" + path + "' is not a readable image: " + problem);
  cv::Mat image;
  try {
    image = cv::imread(path, flags);
  } catch (const cv::Exception& e) {
    throw Error(what + " '" + path + "' is not a readable image: " + openCvMessage(e));
  }
  if (image.empty()) throw Error(what + " '" + path + "' is not a readable image");
  return image;
}

}  // namespace gasp
