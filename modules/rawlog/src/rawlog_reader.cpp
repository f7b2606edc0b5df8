#include "gasp/rawlog/rawlog_reader.h"

#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/serialization/CArchive.h>

#include <deque>
#include <exception>
#include <filesystem>

#include "gasp/core/error.h"
#include "gasp/rawlog/observation_conversion.h"
#include "lazy_load_base_guard.h"

namespace gasp {

struct RawlogReader::Impl {
  mrpt::io::CFileGZInputStream file;
  std::deque<mrpt::obs::CObservation::Ptr> pending;  ///< observations not yet returned
  bool at_end = false;
};

namespace {

/// Class name without namespace ("CObservationOdometry").
std::string className(const mrpt::serialization::CSerializable& obj) {
  const std::string full = obj.GetRuntimeClass()->className;
  const auto colon = full.rfind("::");
  return colon == std::string::npos ? full : full.substr(colon + 2);
}

/// The useful line of an MRPT exception ("==== MRPT exception ====\nMessage:  ...\n<trace>").
std::string mrptMessage(const std::exception& e) {
  const std::string what = e.what();
  const auto m = what.find("Message:");
  if (m == std::string::npos) return what;
  auto begin = what.find_first_not_of(' ', m + 8);
  if (begin == std::string::npos) begin = m + 8;
  return what.substr(begin, what.find('\n', begin) - begin);
}

}  // namespace

RawlogReader::RawlogReader(const std::string& path) : path_(path), impl_(std::make_unique<Impl>()) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::exists(path, ec)) throw Error("rawlog '" + path + "': file not found");
  if (fs::is_directory(path, ec)) throw Error("rawlog '" + path + "': is a directory, not a file");
  if (fs::file_size(path, ec) == 0) throw Error("rawlog '" + path + "': empty file (0 bytes)");
  try {
    if (!impl_->file.open(path)) throw Error("rawlog '" + path + "': cannot open the file");
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    throw Error("rawlog '" + path + "': cannot open the file: " + e.what());
  }
  images_dir_ = findRawlogImagesDirectory(path);

  // Read the first object now so that empty and garbage files fail at open.
  mrpt::serialization::CSerializable::Ptr first;
  try {
    auto ar = mrpt::serialization::archiveFrom(impl_->file);
    first = ar.ReadObject();
  } catch (const mrpt::serialization::CExceptionEOF&) {
    throw Error("rawlog '" + path + "': empty rawlog (no MRPT object in the file)");
  } catch (const std::exception& e) {
    throw Error("rawlog '" + path + "': not an MRPT rawlog or corrupt stream: " + mrptMessage(e));
  }
  if (!first) throw Error("rawlog '" + path + "': not an MRPT rawlog (first object is null)");
  ++objects_read_;
  if (auto sf = std::dynamic_pointer_cast<mrpt::obs::CSensoryFrame>(first)) {
    format_ = RawlogFormat::ActionsSensoryFrames;
    for (const auto& o : *sf) impl_->pending.push_back(o);
  } else if (std::dynamic_pointer_cast<mrpt::obs::CActionCollection>(first)) {
    format_ = RawlogFormat::ActionsSensoryFrames;
    ++skipped_[className(*first)];
  } else if (auto obs = std::dynamic_pointer_cast<mrpt::obs::CObservation>(first)) {
    format_ = RawlogFormat::Observations;
    impl_->pending.push_back(obs);
  } else {
    throw Error("rawlog '" + path + "': not an MRPT rawlog (first object is a " +
                className(*first) +
                ", expected CObservation, CSensoryFrame or CActionCollection)");
  }
}

RawlogReader::~RawlogReader() = default;
RawlogReader::RawlogReader(RawlogReader&&) noexcept = default;
RawlogReader& RawlogReader::operator=(RawlogReader&&) noexcept = default;

std::optional<RgbdFrame> RawlogReader::next() {
  for (;;) {
    while (!impl_->pending.empty()) {
      auto obs = impl_->pending.front();
      impl_->pending.pop_front();
      if (!obs) continue;
      auto scan = std::dynamic_pointer_cast<mrpt::obs::CObservation3DRangeScan>(obs);
      if (!scan) {
        ++skipped_[className(*obs)];
        continue;
      }
      const std::string what = "rawlog '" + path_ + "', 3D scan #" + std::to_string(scans_read_);
      detail::LazyLoadBaseGuard base(images_dir_);
      RgbdFrame frame = frameFromObservation(*scan, what);
      scan->unload();
      ++scans_read_;
      return frame;
    }
    if (impl_->at_end) break;

    mrpt::serialization::CSerializable::Ptr obj;
    try {
      auto ar = mrpt::serialization::archiveFrom(impl_->file);
      obj = ar.ReadObject();
    } catch (const mrpt::serialization::CExceptionEOF&) {
      impl_->at_end = true;
      continue;
    } catch (const std::exception& e) {
      throw Error("rawlog '" + path_ + "': corrupt or truncated stream after " +
                  std::to_string(objects_read_) + " objects: " + mrptMessage(e));
    }
    ++objects_read_;
    if (!obj) continue;
    if (auto sf = std::dynamic_pointer_cast<mrpt::obs::CSensoryFrame>(obj)) {
      for (const auto& o : *sf) impl_->pending.push_back(o);
    } else if (auto obs = std::dynamic_pointer_cast<mrpt::obs::CObservation>(obj)) {
      impl_->pending.push_back(obs);
    } else {
      ++skipped_[className(*obj)];
    }
  }
  if (scans_read_ == 0)
    throw Error("rawlog '" + path_ + "': no CObservation3DRangeScan in the file (it holds " +
                skippedSummary() + ")");
  return std::nullopt;
}

std::string RawlogReader::skippedSummary() const {
  if (skipped_.empty()) return "nothing";
  std::string s;
  for (const auto& [name, count] : skipped_) {
    if (!s.empty()) s += ", ";
    s += std::to_string(count) + " x " + name;
  }
  return s;
}

std::vector<RgbdFrame> readRawlogFrames(const std::string& path) {
  RawlogReader reader(path);
  std::vector<RgbdFrame> frames;
  while (auto f = reader.next()) frames.push_back(std::move(*f));
  return frames;
}

}  // namespace gasp
