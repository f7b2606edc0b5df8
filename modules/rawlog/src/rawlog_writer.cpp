#include "gasp/rawlog/rawlog_writer.h"

#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/serialization/CArchive.h>

#include <cstdio>
#include <exception>
#include <filesystem>
#include <optional>
#include <opencv2/imgcodecs.hpp>

#include "gasp/core/error.h"
#include "gasp/core/image_file.h"
#include "gasp/core/output_file.h"
#include "gasp/rawlog/gz_output_stream.h"
#include "gasp/rawlog/observation_conversion.h"
#include "gasp/rawlog/range_scan.h"

namespace gasp {

struct RawlogWriter::Impl {
  std::optional<OutputFile> file;
  std::optional<GzOutputStream> stream;
};

RawlogWriter::RawlogWriter(const std::string& path, const RawlogWriterOptions& options)
    : path_(path), images_dir_(rawlogImagesDirectory(path)), uncaught_at_construction_(std::uncaught_exceptions()),
      options_(options), impl_(std::make_unique<Impl>()) {
  namespace fs = std::filesystem;
  if (options_.compress_level < 0 || options_.compress_level > 9)
    throw Error("rawlog '" + path + "': compress_level must be 0..9");
  const fs::path parent = fs::path(path).parent_path();
  std::error_code ec;
  if (fs::is_directory(path, ec)) throw Error("rawlog '" + path + "': is a folder, not a file");
  if (!parent.empty()) fs::create_directories(parent, ec);
  if (!parent.empty() && !fs::is_directory(parent, ec))
    throw Error("rawlog '" + path + "': cannot create the output folder '" + parent.string() + "'");
  impl_->file.emplace(path, "rawlog");
  impl_->stream.emplace(*impl_->file, options_.compress_level);
  if (options_.external_storage) {
    fs::create_directories(images_dir_, ec);
    if (!fs::is_directory(images_dir_)) {
      discard();
      throw Error("rawlog '" + path + "': cannot create the images folder '" + images_dir_ + "'");
    }
  }
}

RawlogWriter::~RawlogWriter() {
  if (std::uncaught_exceptions() > uncaught_at_construction_) {
    discard();  // a failed run: the partial file is not published
    return;
  }
  try {
    close();
  } catch (...) {  // destructors must not throw; close() explicitly to see errors
  }
}
RawlogWriter::RawlogWriter(RawlogWriter&&) noexcept = default;
RawlogWriter& RawlogWriter::operator=(RawlogWriter&&) noexcept = default;

void RawlogWriter::checkOpen() const {
  if (!impl_ || !impl_->stream || impl_->file->committed()) throw Error("rawlog '" + path_ + "': writer already closed");
}

void RawlogWriter::write(const RgbdFrame& frame) {
  checkOpen();
  auto obs = observationFromFrame(frame);
  if (options_.points) storePoints3D(*obs);  // from the range image in memory: before it goes external

  if (options_.external_storage) {
    char stem[64];
    std::snprintf(stem, sizeof stem, "_%06zu", frames_written_);
    const std::string base = frame.sensor_label + stem;
    try {
      // MRPT writes IMAGES_DIR/<base>_depth.bin (gz-compressed rows, cols, uint16 data).
      obs->rangeImage_convertToExternalStorage(base + "_depth.bin", images_dir_);
    } catch (const std::exception& e) {
      throw Error("rawlog '" + path_ + "': cannot write the external range image in '" +
                  images_dir_ + "': " + e.what());
    }
    if (obs->hasIntensityImage) {
      const std::string rgb_name = base + "_rgb.png";
      writeImage(images_dir_ + "/" + rgb_name, frame.rgb, "rawlog '" + path_ + "': external rgb image");
      obs->intensityImage.setExternalStorage(rgb_name);
    }
  }

  append(obs);
}

void RawlogWriter::write(const RangeScan& sweep, const std::string& sensor_label) {
  checkOpen();
  if (options_.points)
    append(std::make_shared<mrpt::obs::CObservation3DRangeScan>(toPointsScan(sweep, sensor_label)));
  else
    append(std::make_shared<mrpt::obs::CObservationRotatingScan>(toRotatingScan(sweep, sensor_label)));
}

void RawlogWriter::writePointCloud(const RangeScan& sweep, const std::string& sensor_label) {
  checkOpen();
  append(std::make_shared<mrpt::obs::CObservationPointCloud>(toPointCloud(sweep, sensor_label)));
}

void RawlogWriter::append(const std::shared_ptr<mrpt::obs::CObservation>& obs) {
  try {
    auto ar = mrpt::serialization::archiveFrom(*impl_->stream);
    if (options_.format == RawlogFormat::ActionsSensoryFrames) {
      mrpt::obs::CActionCollection actions;
      mrpt::obs::CSensoryFrame sf;
      sf.insert(obs);
      ar << actions << sf;
    } else {
      ar << *obs;
    }
  } catch (const Error&) {
    throw;  // names the file and the system's reason (OutputFile)
  } catch (const std::exception& e) {
    throw Error("rawlog '" + path_ + "': write failed: " + exceptionMessage(e));
  }
  ++frames_written_;
}

void RawlogWriter::close() {
  if (!impl_ || !impl_->stream) return;
  try {
    impl_->stream->finish();  // ends the gzip stream, checks, fsyncs and renames (OutputFile::commit())
  } catch (...) {
    impl_->stream.reset();  // closed: the file was dropped
    throw;
  }
  impl_->stream.reset();
}

void RawlogWriter::discard() {
  if (!impl_ || !impl_->stream) return;
  impl_->stream.reset();
  impl_->file->discard();
}

}  // namespace gasp
