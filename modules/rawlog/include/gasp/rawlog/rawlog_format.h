#pragma once
/// \file rawlog_format.h The two MRPT rawlog layouts and the "<name>_Images" folder convention.
#include <string>

namespace gasp {

/// MRPT rawlog layouts (both may be gzip-compressed or plain).
enum class RawlogFormat {
  /// #1: alternating CActionCollection and CSensoryFrame objects.
  ActionsSensoryFrames = 1,
  /// #2: a plain stream of CObservation objects (what MRPT grabbers write today).
  Observations = 2,
};

/// "1" or "2" -> the format; throws gasp::Error otherwise.
RawlogFormat rawlogFormatFromNumber(int number);

/// MRPT's folder for externally stored images of a rawlog: DIR/STEM_Images for DIR/STEM.EXT
/// (what mrpt::obs::CRawlog::detectImagesDirectory() looks for first).
std::string rawlogImagesDirectory(const std::string& rawlog_path);

/// The existing external-storage folder of a rawlog, searched like
/// mrpt::obs::CRawlog::detectImagesDirectory(): DIR/STEM_Images, DIR/STEM_images,
/// DIR/STEM_IMAGES, else DIR/Images. (MRPT 2.5.8's own function only finds the folder when the
/// rawlog path has no directory part, so GASP does not use it.)
std::string findRawlogImagesDirectory(const std::string& rawlog_path);

}  // namespace gasp
