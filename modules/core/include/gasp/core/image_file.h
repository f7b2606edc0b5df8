#pragma once
/// \file image_file.h Reading and writing image files with errors that name the file
/// (gasp::Error), never an OpenCV exception or a silent failure.
#include <opencv2/core.hpp>

#include <string>

#include "gasp/core/output_file.h"

namespace gasp {

/// Throws gasp::Error when OpenCV has no writer for the file name's extension ("<what> 'x.txt':
/// no image format for this file name; use .png, .jpg, ..."). For options checked before the work.
void requireImageWriter(const std::string& path, const std::string& what);

/// The image encoded in the format of `path`'s extension and written whole or not at all
/// (gasp/core/output_file.h). Errors: no writer for the extension, OpenCV's exception, a failed
/// write.
void writeImage(const std::string& path, const cv::Mat& image, const std::string& what = "image");
/// The same into an output opened before the work (its path's extension chooses the format);
/// commits it.
void writeImage(OutputFile& out, const cv::Mat& image, const std::string& what = "image");

/// cv::imread with errors: a file that cannot be opened, OpenCV's exception (e.g. a header
/// claiming more pixels than OpenCV reads), not a readable image.
cv::Mat readImage(const std::string& path, int flags, const std::string& what = "image");

}  // namespace gasp
