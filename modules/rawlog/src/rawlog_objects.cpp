#include "gasp/rawlog/rawlog_objects.h"

#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/obs/CObservationRotatingScan.h>
#include <mrpt/serialization/CArchive.h>

#include <cstdint>
#include <exception>
#include <filesystem>

#include "content_scan.h"
#include "gasp/core/error.h"
#include "lookahead_stream.h"
#include "object_size_check.h"

namespace gasp {

struct RawlogObjects::Impl {
  mrpt::io::CFileGZInputStream file;
  detail::LookaheadStream stream{file};  ///< what MRPT reads: the file, its next bytes checked first
  detail::ContentScan content;           ///< the content's length (and damage), scanned at open
  bool at_end = false;
};

namespace {

/// "X" of MRPT's "Stored object has class 'X' which is not registered!", or "".
std::string unregisteredClass(const std::string& message) {
  if (message.find("not registered") == std::string::npos) return "";
  const auto open = message.find('\'');
  const auto close = open == std::string::npos ? open : message.find('\'', open + 1);
  return close == std::string::npos ? "" : message.substr(open + 1, close - open - 1);
}

}  // namespace

std::string rawlogClassName(const mrpt::serialization::CSerializable& object) {
  const std::string full = object.GetRuntimeClass()->className;
  const auto colon = full.rfind("::");
  return colon == std::string::npos ? full : full.substr(colon + 2);
}

RawlogObjects::RawlogObjects(const std::string& path) : path_(path), impl_(std::make_unique<Impl>()) {
  // MRPT registers the observation classes of mrpt-maps (CObservationRotatingScan,
  // CObservationPointCloud, ...) when that library is loaded. Naming one keeps it linked into
  // every program that reads rawlogs, so their objects are read and skipped by name instead of
  // stopping the read as an unknown class.
  static_cast<void>(CLASS_ID(mrpt::obs::CObservationRotatingScan));
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
  // The content's length bounds every size an object may claim (object_size_check.h). A damaged
  // gzip stream is reported where MRPT's reading ends, after the objects before the damage.
  impl_->content = detail::scanContent(path);
}

RawlogObjects::~RawlogObjects() = default;
RawlogObjects::RawlogObjects(RawlogObjects&&) noexcept = default;
RawlogObjects& RawlogObjects::operator=(RawlogObjects&&) noexcept = default;

mrpt::serialization::CSerializable::Ptr RawlogObjects::next() {
  while (!impl_->at_end) {
    mrpt::serialization::CSerializable::Ptr object;
    const std::uint64_t start = impl_->stream.getPosition();  // of the object, in the content
    const std::uint64_t length = impl_->content.length;
    // Sizes MRPT would allocate from, checked against what the stream holds (no length prefix).
    const std::string problem = detail::ObjectSizeCheck(impl_->stream, length > start ? length - start : 0).run();
    if (!problem.empty()) {
      impl_->at_end = true;
      // In a damaged gzip stream the content ends early: the damage is the cause to report.
      if (!impl_->content.error.empty()) throw Error("rawlog '" + path_ + "': " + impl_->content.error);
      throw Error("rawlog '" + path_ + "': object #" + std::to_string(objects_read_) + " (at byte " +
                  std::to_string(start) + " of " + std::to_string(length) + "): corrupt or truncated: " + problem);
    }
    try {
      auto archive = mrpt::serialization::archiveFrom(impl_->stream);
      object = archive.ReadObject();
    } catch (const mrpt::serialization::CExceptionEOF&) {
      // The end, if the object was to start where the content ends. MRPT also throws "EOF" for
      // an object cut short, and CFileGZInputStream ends early at a damaged gzip stream.
      impl_->at_end = true;
      if (!impl_->content.error.empty()) throw Error("rawlog '" + path_ + "': " + impl_->content.error);
      if (start != length)
        throw Error("rawlog '" + path_ + "': corrupt or truncated stream after " + std::to_string(objects_read_) +
                    " objects: the next object, at byte " + std::to_string(start) + " of " + std::to_string(length) +
                    ", ends early");
      break;
    } catch (const std::exception& e) {
      impl_->at_end = true;
      if (!impl_->content.error.empty()) throw Error("rawlog '" + path_ + "': " + impl_->content.error);
      const std::string message = exceptionMessage(e);
      const std::string unknown = unregisteredClass(message);
      if (!unknown.empty())
        throw Error("rawlog '" + path_ + "': object #" + std::to_string(objects_read_) + " is a '" + unknown +
                    "', a class this program does not know (from a newer MRPT or a plugin not loaded); the "
                    "objects after it cannot be read");
      if (objects_read_ == 0) throw Error("rawlog '" + path_ + "': not an MRPT rawlog, or a corrupt or truncated one: " + message);
      throw Error("rawlog '" + path_ + "': corrupt or truncated stream after " + std::to_string(objects_read_) +
                  " objects: " + message);
    }
    ++objects_read_;
    if (object) return object;  // MRPT writes a null pointer as an object too: skipped
  }
  return nullptr;
}

}  // namespace gasp
