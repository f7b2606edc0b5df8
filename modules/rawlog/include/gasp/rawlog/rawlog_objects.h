#pragma once
/// \file rawlog_objects.h The MRPT objects of a rawlog file, one by one, with errors that say
/// where and why reading stopped.
#include <mrpt/serialization/CSerializable.h>

#include <cstddef>
#include <memory>
#include <string>

namespace gasp {

/// Reads the serialized objects of a rawlog (gzip-compressed or plain) in file order.
///
/// Unlike mrpt::obs::CRawlog::getActionObservationPairOrObservation(), which returns false for
/// the end of the file and for any error alike, a truncated or corrupt file is an error here.
/// Errors (gasp::Error, naming the file): missing file, a directory, an empty file (0 bytes),
/// a file that cannot be opened; while reading, a truncated or corrupt stream (after how many
/// objects, with MRPT's message) or an object of a class this program does not know (its name).
class RawlogObjects {
 public:
  explicit RawlogObjects(const std::string& path);
  ~RawlogObjects();
  RawlogObjects(RawlogObjects&&) noexcept;
  RawlogObjects& operator=(RawlogObjects&&) noexcept;

  /// The next object, or nullptr at the end of the file (a clean end between two objects).
  mrpt::serialization::CSerializable::Ptr next();

  const std::string& path() const { return path_; }
  /// Objects returned so far.
  std::size_t objectsRead() const { return objects_read_; }

 private:
  struct Impl;
  std::string path_;
  std::size_t objects_read_ = 0;
  std::unique_ptr<Impl> impl_;
};

/// Class name without namespace ("CObservationOdometry").
std::string rawlogClassName(const mrpt::serialization::CSerializable& object);

}  // namespace gasp
