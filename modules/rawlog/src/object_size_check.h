#pragma once
/// \file object_size_check.h (private) The size fields of a rawlog object checked against the
/// bytes that remain in the stream, before MRPT deserialises it.
///
/// MRPT's serialisation has no length prefix: CObservation3DRangeScan::serializeFrom() reads
/// `rows` and `cols` and calls rangeImage_setSize(rows, cols) before it reads the pixels, so one
/// corrupted size field makes it allocate gigabytes or, the product overflowing Eigen's int
/// sizes, crash (issue 44: a byte flipped at offset 171 of a rawlog segfaulted). A count or an
/// image that needs more bytes than the rest of the stream holds cannot be right, so it is
/// refused here. The check walks the object's header fields as MRPT 2.5 reads them (an object:
/// 0x80 | name length, class name, version byte, fields, 0x88; or MRPT's pre-0.5.5 header) and
/// looks only at what MRPT will allocate from:
///  - CObservation3DRangeScan: in every version the 3D points' count; in versions 9 and 10 (MRPT
///    2.x) also the range image's rows x cols (and each side on its own, Eigen's sizes being int),
///    then the intensity and confidence images (CImage versions 6-9: raw sizes, JPEG byte count,
///    external file name), the two cameras (TCamera versions 4-6: camera name), the relative pose,
///    the sensor label, the external file names, the pixel labels (size, label names) and the
///    extra range layers (version 10);
///  - CSensoryFrame (versions 0-2) and CActionCollection (version 0): the count of objects, then
///    each object inside as far as they can be followed.
/// Every object's class must be one a rawlog holds there (an observation, a sensory frame or an
/// action collection; observations inside a sensory frame, actions inside a collection): MRPT
/// would deserialise any registered class the name says, with its own size fields, before the
/// reader could look at its type.
/// An object cut inside a field is an error too (MRPT would go on with a partial value). A class,
/// a version or a nested layout it does not know (a JPEG's own header, a scan before version 9
/// after its points, other observation classes) is left to MRPT as before: it does not make a
/// valid file an error. Inside a version 9/10 scan (MRPT 2), a pose, camera or image of a version
/// MRPT 2 does not write is an error: MRPT would read the sizes that follow from the wrong bytes.
/// (The poses: CPose3D versions 2 and 3.)
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>

#include <mrpt/obs/CAction.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CObservation.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/rtti/CObject.h>

#include "lookahead_stream.h"

namespace gasp::detail {

class ObjectSizeCheck {
 public:
  /// `remaining`: the bytes of the content from the read position to its end.
  ObjectSizeCheck(LookaheadStream& stream, std::uint64_t remaining) : s_(stream), remaining_(remaining) {}

  /// "" when the sizes fit (or the object is not one it knows), else what does not fit (a corrupt
  /// size field, or the file cut inside the object).
  std::string run() {
    cursor_ = 0;
    cut_ = false;
    std::string problem;
    object(0, problem);
    // Cut inside a field: MRPT reads a partial field without noticing (CArchive::ReadBuffer throws
    // only when nothing at all is read) and allocates from the garbage.
    if (problem.empty() && cut_)
      problem = "the stream ends inside this object (" + bytes(cursor_) + " of it read, " + bytes(remaining_) +
                " in the rest of the stream, a field needs more)";
    return problem;
  }

 private:
  LookaheadStream& s_;
  std::uint64_t remaining_;
  std::uint64_t cursor_ = 0;  ///< bytes after the read position looked at so far

  std::uint64_t left() const { return remaining_ > cursor_ ? remaining_ - cursor_ : 0; }

  bool cut_ = false;  ///< a field or block went past the end of the stream (after cursor_ > 0)

  /// `count` bytes at the cursor into `out`, or false (and cut_ when the object had begun).
  bool take(void* out, std::size_t count) {
    if (count > left() || s_.peek(cursor_, out, count) != count) {
      cut_ = cut_ || cursor_ > 0;  // nothing at all: the clean end of the file
      return false;
    }
    cursor_ += count;
    return true;
  }
  template <class T>
  bool read(T& value) {
    return take(&value, sizeof(T));
  }
  bool skip(std::uint64_t bytes) {
    if (bytes > left()) {
      cut_ = true;
      return false;
    }
    cursor_ += bytes;
    return true;
  }
  /// An object header, as MRPT reads it: 0x80 | name length, the name, a version byte; or (before
  /// MRPT 0.5.5, `old`) the name length, three zero bytes, the name, an int32 version and no end
  /// flag after the fields. False when it is not one (null objects included).
  bool header(std::string& name, std::uint8_t& version, bool& old) {
    std::uint8_t lead = 0;
    if (!read(lead) || (lead & 0x7f) == 0 || (lead & 0x7f) > 120) return false;
    old = (lead & 0x80) == 0;
    std::uint8_t zeros[3] = {1, 1, 1};
    if (old && (!take(zeros, 3) || zeros[0] || zeros[1] || zeros[2])) return false;
    name.assign(lead & 0x7f, '\0');
    if (!take(name.data(), name.size())) return false;
    if (!old) return read(version);
    std::int32_t old_version = -1;
    if (!read(old_version) || old_version < 0 || old_version >= 255) return false;
    version = static_cast<std::uint8_t>(old_version);
    return true;
  }
  bool header(std::string& name, std::uint8_t& version) {
    bool old = false;
    return header(name, version, old);
  }
  /// The end flag 0x88 after an object's fields (none in the old format).
  bool endFlag(bool old) {
    std::uint8_t end = 0;
    return old || (read(end) && end == 0x88);
  }
  static std::string bytes(std::uint64_t n) { return std::to_string(n) + " bytes"; }

  /// One object from its header to its end flag. False when it cannot be followed to its end (a
  /// class or layout it does not know, or bytes missing: MRPT reports those), with `problem` set
  /// when a size does not fit.
  /// What an object may be where it is: a rawlog entry at the top, an observation inside a
  /// sensory frame, an action inside an action collection. MRPT deserialises whatever class the
  /// name says (any registered class, with its own size fields: fuzz_rawlog named a CRawlog,
  /// whose object count asked for 27 GB) before the reader can look at its type.
  enum class Place { kEntry, kInSensoryFrame, kInActionCollection };

  static std::string placeProblem(Place place, const std::string& name) {
    const char* wanted = place == Place::kEntry                ? "an observation, a sensory frame or an action collection"
                         : place == Place::kInSensoryFrame     ? "an observation (inside a sensory frame)"
                                                               : "an action (inside an action collection)";
    return "a '" + name + "' where a rawlog holds " + wanted;
  }

  bool object(int depth, std::string& problem, Place place = Place::kEntry) {
    std::string name;
    std::uint8_t version = 0;
    bool old = false;
    if (!header(name, version, old)) return false;
    // MRPT finds the class by the name as a C string (up to a zero byte), ignoring the namespace.
    name.resize(std::min(name.size(), name.find('\0')));
    if (const mrpt::rtti::TRuntimeClassId* cls = mrpt::rtti::findRegisteredClass(name)) {
      using namespace mrpt::obs;
      const bool observation = cls->derivedFrom(CLASS_ID(CObservation));
      const bool fits = place == Place::kInSensoryFrame       ? observation
                        : place == Place::kInActionCollection ? cls->derivedFrom(CLASS_ID(CAction))
                                                              : observation || cls == CLASS_ID(CSensoryFrame) ||
                                                                    cls == CLASS_ID(CActionCollection);
      if (!fits) {
        problem = placeProblem(place, cls->className);
        return false;
      }
    }  // a class MRPT does not know: MRPT says so
    const auto colon = name.rfind("::");
    if (colon != std::string::npos) name = name.substr(colon + 2);
    if (name == "CObservation3DRangeScan") {
      const std::uint64_t begin = cursor_;
      if (rangeScan(version, old, problem)) return true;
      // A version 9 or 10 scan (MRPT 2) is followed field by field as MRPT 2 reads it: a field
      // that does not fit that layout would send MRPT reading sizes from the wrong bytes.
      if (problem.empty() && !cut_ && (version == 9 || version == 10))
        problem = "CObservation3DRangeScan: the fields from byte " + std::to_string(cursor_ - begin) +
                  " of this version " + std::to_string(version) + " scan are not laid out as MRPT 2 writes them";
      return false;
    }
    if (depth < kMaxDepth &&
        ((name == "CSensoryFrame" && version <= 2) || (name == "CActionCollection" && version == 0))) {
      // CSensoryFrame before version 2: an ID (uint32), in version 0 also a timestamp (uint64).
      if (name == "CSensoryFrame" && !skip((version < 2 ? 4 : 0) + (version == 0 ? 8 : 0))) return false;
      std::uint32_t n = 0;
      if (!read(n)) return false;
      if (n > left()) {  // every object takes at least one byte
        problem = name + " claims " + std::to_string(n) + " objects but " + bytes(left()) + " remain in the stream";
        return false;
      }
      const Place inside = name == "CSensoryFrame" ? Place::kInSensoryFrame : Place::kInActionCollection;
      for (std::uint32_t i = 0; i < n; ++i)  // each inside, as far as they can be followed
        if (!object(depth + 1, problem, inside)) return false;
      return endFlag(old);
    }
    return false;
  }
  static constexpr int kMaxDepth = 64;  ///< sensory frames inside sensory frames: followed this deep

  bool rangeScan(std::uint8_t version, bool old, std::string& problem) {
    if (version > 10) return false;  // MRPT refuses it
    float max_range = 0;
    if (!read(max_range)) return false;
    const std::string what = "CObservation3DRangeScan: ";
    if (!pose(what + "sensorPose", problem, version >= 9)) return false;
    std::uint8_t has_points = 1;  // version 0: always
    if (version > 0 && !flag(what + "hasPoints3D", has_points, problem)) return false;
    if (has_points) {
      std::uint32_t n = 0;
      if (!read(n)) return false;
      // x, y, z floats; version 0 a validity byte each, version 8 on two uint16 pixel indices.
      const std::uint64_t each = 3 * sizeof(float) + (version == 0 ? 1 : 0) + (version >= 8 ? 4 : 0);
      const std::uint64_t need = std::uint64_t{n} * each;
      if (need > left()) {
        problem = what + std::to_string(n) + " 3D points need " + bytes(need) + " but " + bytes(left()) + " remain";
        return false;
      }
      skip(need);
    }
    if (version < 9) return false;  // then a CMatrixF range image and older fields: left to MRPT
    std::uint8_t has_range = 0;
    float range_units = 0;
    if (!flag(what + "hasRangeImage", has_range, problem) || !read(range_units)) return false;
    if (has_range && !rangeImage(what + "range image", problem)) return false;
    std::uint8_t has_image = 0;
    if (!flag(what + "hasIntensityImage", has_image, problem) || (has_image && !image(what + "intensity image", problem)))
      return false;
    if (!flag(what + "hasConfidenceImage", has_image, problem) || (has_image && !image(what + "confidence image", problem)))
      return false;
    for (const char* camera : {"cameraParams", "cameraParamsIntensity"})
      if (!this->camera(what + camera, problem)) return false;
    if (!pose(what + "relativePoseIntensityWRTDepth", problem)) return false;
    if (!skip(sizeof(float) + sizeof(std::uint64_t))) return false;  // stdError, timestamp
    if (!string(what + "sensorLabel", problem)) return false;
    for (const char* file : {"points3D external file", "rangeImage external file"})
      if (std::uint8_t stored = 0; !flag(what + file + " flag", stored, problem) || !string(what + file, problem))
        return false;
    std::uint8_t has_labels = 0;
    std::uint8_t range_is_depth = 0;
    if (!flag(what + "range_is_depth", range_is_depth, problem) || !skip(1) ||  // then the intensity channel
        !flag(what + "pixelLabels flag", has_labels, problem) || (has_labels && !labels(what + "pixelLabels", problem)))
      return false;
    if (version >= 10) {
      std::uint8_t layers = 0;
      if (!read(layers)) return false;
      for (int i = 0; i < layers; ++i)
        if (!string(what + "range layer name", problem) ||
            !rangeImage(what + "range layer #" + std::to_string(i), problem))
          return false;
    }
    return endFlag(old);
  }

  /// A nested object's version that no MRPT writing a version 9 or 10 scan (MRPT 2) writes: the
  /// layout of what follows is unknown, and MRPT would read sizes from the wrong bytes. (MRPT
  /// reads a nested object of a known type without checking its class name, so neither does this.)
  bool unknownVersion(const std::string& what, const char* type, std::uint8_t version, std::string& problem) {
    problem = what + ": a " + type + " of serialisation version " + std::to_string(version) +
              ", which MRPT 2 does not write in a version 9 or 10 scan (a corrupt byte)";
    return false;
  }

  /// A mrpt::poses::CPose3D object (version 2: 7 doubles, 3: 12 doubles). False when it cannot be
  /// followed (problem set when it is not a layout MRPT 2 writes).
  bool pose(const std::string& what, std::string& problem, bool mrpt2 = true) {
    std::string name;
    std::uint8_t version = 0;
    bool old = false;
    if (!header(name, version, old)) return false;
    if (version != 2 && version != 3) return mrpt2 ? unknownVersion(what, "CPose3D", version, problem) : false;
    return skip((version == 2 ? 7 : 12) * sizeof(double)) && endFlag(old);
  }

  /// rows, cols (uint32) and rows x cols uint16 values. False when they do not fit (problem set)
  /// or cannot be read.
  bool rangeImage(const std::string& what, std::string& problem) {
    std::uint32_t rows = 0, cols = 0;
    if (!read(rows) || !read(cols)) return false;
    const std::uint64_t need = std::uint64_t{rows} * cols * sizeof(std::uint16_t);
    const std::uint64_t max_side = std::numeric_limits<std::int32_t>::max();
    if (need > left() || rows > max_side || cols > max_side) {
      problem = what + " of " + std::to_string(rows) + " x " + std::to_string(cols) + " pixels needs " + bytes(need) +
                " but " + bytes(left()) + " remain in the stream";
      return false;
    }
    return skip(need);
  }

  /// TPixelLabelInfo as MRPT 2 writes it: version 1, bytes per pixel (1, 2, 4, 8), rows, cols
  /// (uint32) and the pixels' bit fields, then the label names as a std::map<uint32_t,
  /// std::string> (three type-name strings, a count, key and string pairs). False when it cannot
  /// be followed (problem set when a size does not fit).
  bool labels(const std::string& what, std::string& problem) {
    std::uint8_t version = 0, bytes_per_pixel = 0;
    if (!read(version) || version != 1 || !read(bytes_per_pixel)) return false;
    if (bytes_per_pixel != 1 && bytes_per_pixel != 2 && bytes_per_pixel != 4 && bytes_per_pixel != 8) return false;
    std::uint32_t rows = 0, cols = 0;
    if (!read(rows) || !read(cols)) return false;
    const std::uint64_t need = std::uint64_t{rows} * cols * bytes_per_pixel;
    const std::uint64_t max_side = std::numeric_limits<std::int32_t>::max();
    if (need > left() || rows > max_side || cols > max_side) {
      problem = what + " of " + std::to_string(rows) + " x " + std::to_string(cols) + " pixels needs " + bytes(need) +
                " but " + bytes(left()) + " remain in the stream";
      return false;
    }
    if (!skip(need)) return false;
    for (int i = 0; i < 3; ++i)
      if (!string(what + " names' type", problem)) return false;
    std::uint32_t n = 0;
    if (!read(n)) return false;
    if (std::uint64_t{n} * 8 > left()) {  // a key and a string length each
      problem = what + " claims " + std::to_string(n) + " label names but " + bytes(left()) + " remain in the stream";
      return false;
    }
    for (std::uint32_t i = 0; i < n; ++i)
      if (!skip(4) || !string(what + " name", problem)) return false;
    return true;
  }

  /// A bool as MRPT writes it: one byte, 0 or 1. MRPT reads the byte into a bool as it is, and
  /// any other value there is undefined behaviour where the bool is used (UBSan in fuzz_rawlog:
  /// hasIntensityImage of 126). False when it cannot be read or is not 0 or 1 (problem set).
  bool flag(const std::string& what, std::uint8_t& value, std::string& problem) {
    if (!read(value)) return false;
    if (value > 1) {
      problem = what + " is " + std::to_string(value) + ", not 0 or 1 (a corrupt byte)";
      return false;
    }
    return true;
  }

  /// A string (uint32 length, bytes). False when it cannot be followed (problem set when too long).
  bool string(const std::string& what, std::string& problem) {
    std::uint32_t n = 0;
    if (!read(n)) return false;
    if (n > left()) {
      problem = what + " claims " + bytes(n) + " but " + bytes(left()) + " remain in the stream";
      return false;
    }
    return skip(n);
  }

  /// A mrpt::img::CImage object (versions 6 to 9). False when it cannot be followed (problem set
  /// when a size does not fit or the version is not one MRPT 2 writes).
  bool image(const std::string& what, std::string& problem) {
    std::string name;
    std::uint8_t version = 0;
    bool old = false;
    if (!header(name, version, old)) return false;
    if (version < 6 || version > 9) return unknownVersion(what, "CImage", version, problem);
    std::uint8_t external = 0, colour = 0;
    if (!flag(what + " external-storage flag", external, problem)) return false;
    if (external) return string(what + " file name", problem) && endFlag(old);
    if (!read(colour)) return false;
    std::int32_t width = 1, height = 1;
    if ((!colour || version >= 7) && (!read(width) || !read(height))) return false;  // colour before 7: JPEG
    const std::string size = " of " + std::to_string(width) + " x " + std::to_string(height) + " pixels";
    if (!colour) {  // grey: width, height, origin, byte count, depth (version 9), zip flag, bytes
      std::int32_t origin = 0, count = 0, depth = 0;
      std::uint8_t zip = 0;
      if (!read(origin) || !read(count) || (version >= 9 && !read(depth)) || !read(zip)) return false;
      const std::uint64_t pixels = width < 0 || height < 0 ? 0 : std::uint64_t(width) * std::uint64_t(height);
      if (width < 0 || height < 0 || count < 0 || pixels > left() || std::uint64_t(count) > left()) {
        problem = what + size + " (" + bytes(std::uint64_t(std::max(count, 0))) + ") needs more than the " +
                  bytes(left()) + " that remain in the stream";
        return false;
      }
      if (zip) return false;  // MRPT refuses it
      return skip(std::uint64_t(count)) && endFlag(old);
    }
    if (width >= 1 && height >= 1) {  // JPEG: byte count and bytes (the JPEG's own header: OpenCV's)
      std::uint32_t n = 0;
      if (!read(n)) return false;
      if (n > left()) {
        problem = what + " (JPEG) claims " + bytes(n) + " but " + bytes(left()) + " remain in the stream";
        return false;
      }
      return skip(n) && endFlag(old);
    }
    if (width < 0 && height < 0) {  // raw BGR, the sizes negated
      const std::uint64_t need = width == std::numeric_limits<std::int32_t>::min() ||
                                         height == std::numeric_limits<std::int32_t>::min()
                                     ? std::numeric_limits<std::uint64_t>::max()
                                     : std::uint64_t(-std::int64_t{width}) * std::uint64_t(-std::int64_t{height}) * 3;
      if (need > left()) {
        problem = what + " of " + std::to_string(-std::int64_t{width}) + " x " + std::to_string(-std::int64_t{height}) +
                  " BGR pixels needs " + (need == std::numeric_limits<std::uint64_t>::max() ? std::string("more than 2^64 bytes") : bytes(need)) +
                  " but " + bytes(left()) + " remain in the stream";
        return false;
      }
      return skip(need) && endFlag(old);
    }
    return false;  // an empty colour image of one negative side: MRPT's (OpenCV refuses it)
  }

  /// A mrpt::img::TCamera object (versions 4 to 6). False when it cannot be followed.
  bool camera(const std::string& what, std::string& problem) {
    std::string name;
    std::uint8_t version = 0;
    bool old = false;
    if (!header(name, version, old)) return false;
    if (version < 4 || version > 6) return unknownVersion(what, "TCamera", version, problem);
    if (!skip(13 * sizeof(double) + 2 * sizeof(std::uint32_t))) return false;  // focal length, 8 dist, fx fy cx cy, size
    if (version >= 5 && !string(what + " camera name", problem)) return false;
    return skip(version >= 6 ? 1 : 0) && endFlag(old);
  }
};

}  // namespace gasp::detail
