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
///  - CObservation3DRangeScan, every version MRPT 2.5 reads (0 to 10, MRPT 1 and 2): the 3D
///    points' count, the range image (a CMatrixF object before version 9, rows x cols uint16s
///    from 9, each side within Eigen's int sizes), the intensity and confidence images (CImage
///    versions 0-9 and 100: raw sizes, byte counts, JPEG byte count, external file name), the
///    cameras (TCamera versions 0-6: intrinsics matrices, camera name), the poses (CPose3D
///    versions 0-3, the first two a matrix object), the sensor label, the external file names,
///    the pixel labels (size, label names) and the extra range layers (version 10);
///  - CSensoryFrame (versions 0-2) and CActionCollection (version 0): the count of objects, then
///    each object inside as far as they can be followed.
/// Every object's class must be one a rawlog holds there (an observation, a sensory frame or an
/// action collection; observations inside a sensory frame, actions inside a collection): MRPT
/// would deserialise any registered class the name says, with its own size fields, before the
/// reader could look at its type.
/// An object cut inside a field is an error too (MRPT would go on with a partial value). A class
/// it does not know (other observation classes), a sensory frame version it does not know or a
/// JPEG's own header is left to MRPT: it does not make a valid file an error. Inside a scan, a
/// field that does not follow the layout of its version (a pose, camera, image or matrix of a
/// version MRPT does not read, a zipped image MRPT refuses) is an error: MRPT would read the
/// sizes that follow from the wrong bytes, or refuse the object.
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
      // A scan is followed field by field as MRPT reads its version: a field that does not fit
      // that layout would send MRPT reading sizes from the wrong bytes.
      if (problem.empty() && !cut_ && version <= 10)
        problem = "CObservation3DRangeScan: the fields from byte " + std::to_string(cursor_ - begin) +
                  " of this version " + std::to_string(version) + " scan are not laid out as MRPT reads them";
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

  /// A CObservation3DRangeScan of any version MRPT 2.5 reads (0 to 10), field by field as its
  /// serializeFrom() reads them. True when followed to its end flag.
  bool rangeScan(std::uint8_t version, bool old, std::string& problem) {
    if (version > 10) return false;  // MRPT refuses it
    float max_range = 0;
    if (!read(max_range)) return false;
    const std::string what = "CObservation3DRangeScan: ";
    if (!pose(what + "sensorPose", problem)) return false;
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
    if (version >= 1) {
      std::uint8_t has_range = 0;
      if (!flag(what + "hasRangeImage", has_range, problem)) return false;
      float range_units = 0;
      if (version >= 9 && !read(range_units)) return false;
      if (has_range) {
        // Before version 9 a CMatrixF object of float ranges, from version 9 rows, cols, uint16s.
        if (version < 9 ? !matrix(what + "range image", sizeof(float), problem)
                        : !rangeImage(what + "range image", problem))
          return false;
      }
      std::uint8_t has_image = 0;
      if (!flag(what + "hasIntensityImage", has_image, problem) ||
          (has_image && !image(what + "intensity image", problem)))
        return false;
      if (!flag(what + "hasConfidenceImage", has_image, problem) ||
          (has_image && !image(what + "confidence image", problem)))
        return false;
      if (version >= 2 && !camera(what + "cameraParams", problem)) return false;
      if (version >= 4 && (!camera(what + "cameraParamsIntensity", problem) ||
                           !pose(what + "relativePoseIntensityWRTDepth", problem)))
        return false;
    }
    if (!skip(sizeof(float) + sizeof(std::uint64_t))) return false;  // stdError, timestamp
    if (!string(what + "sensorLabel", problem)) return false;
    if (version >= 3)
      for (const char* file : {"points3D external file", "rangeImage external file"})
        if (std::uint8_t stored = 0; !flag(what + file + " flag", stored, problem) || !string(what + file, problem))
          return false;
    std::uint8_t range_is_depth = 0;
    if (version >= 5 && !flag(what + "range_is_depth", range_is_depth, problem)) return false;
    if (version >= 6 && !skip(1)) return false;  // the intensity channel
    std::uint8_t has_labels = 0;
    if (version >= 7 && (!flag(what + "pixelLabels flag", has_labels, problem) ||
                         (has_labels && !labels(what + "pixelLabels", problem))))
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

  /// A nested object's version that MRPT 2.5 does not read: the layout of what follows is
  /// unknown, and MRPT would refuse it. (MRPT reads a nested object of a known type without
  /// checking its class name, so neither does this.)
  bool unknownVersion(const std::string& what, const char* type, std::uint8_t version, std::string& problem) {
    problem = what + ": a " + type + " of serialisation version " + std::to_string(version) +
              ", which MRPT does not read (a corrupt byte)";
    return false;
  }

  /// A mrpt::poses::CPose3D object: version 0 a 4 x 4 CMatrixF object, 1 a 4 x 4 CMatrixD object,
  /// 2 seven doubles, 3 twelve doubles. False when it cannot be followed (problem set when a size
  /// does not fit or the version is not one MRPT reads).
  bool pose(const std::string& what, std::string& problem) {
    std::string name;
    std::uint8_t version = 0;
    bool old = false;
    if (!header(name, version, old)) return false;
    if (version > 3) return unknownVersion(what, "CPose3D", version, problem);
    const bool fields = version == 0   ? matrix(what + " matrix", sizeof(float), problem)
                        : version == 1 ? matrix(what + " matrix", sizeof(double), problem)
                                       : skip((version == 2 ? 7 : 12) * sizeof(double));
    return fields && endFlag(old);
  }

  /// A mrpt::math::CMatrixF or CMatrixD object (version 0: rows, cols (uint32), rows x cols
  /// values of `value_bytes`). False when it cannot be followed (problem set when the values
  /// need more bytes than remain or the version is not 0).
  bool matrix(const std::string& what, std::uint64_t value_bytes, std::string& problem) {
    std::string name;
    std::uint8_t version = 0;
    bool old = false;
    if (!header(name, version, old)) return false;
    if (version != 0) return unknownVersion(what, "matrix", version, problem);
    return grid(what, value_bytes, "values", problem) && endFlag(old);
  }

  /// rows, cols (uint32) and rows x cols values of `value_bytes` each, as MRPT reads a matrix or
  /// an image into memory it allocates from the two sizes. False when they do not fit (problem
  /// set: more bytes than remain, or a side beyond Eigen's int) or cannot be read.
  bool grid(const std::string& what, std::uint64_t value_bytes, const char* unit, std::string& problem) {
    std::uint32_t rows = 0, cols = 0;
    if (!read(rows) || !read(cols)) return false;
    const std::uint64_t need = std::uint64_t{rows} * cols * value_bytes;
    const std::uint64_t max_side = std::numeric_limits<std::int32_t>::max();
    if (need > left() || rows > max_side || cols > max_side) {
      problem = what + " of " + std::to_string(rows) + " x " + std::to_string(cols) + " " + unit + " needs " +
                bytes(need) + " but " + bytes(left()) + " remain in the stream";
      return false;
    }
    return skip(need);
  }

  /// rows, cols (uint32) and rows x cols uint16 values. False when they do not fit (problem set)
  /// or cannot be read.
  bool rangeImage(const std::string& what, std::string& problem) {
    return grid(what, sizeof(std::uint16_t), "pixels", problem);
  }

  /// TPixelLabelInfo as MRPT reads it: version 1, bytes per pixel (1 to 8), rows, cols
  /// (uint32) and the pixels' bit fields, then the label names as a std::map<uint32_t,
  /// std::string> (three type-name strings, a count, key and string pairs). False when it cannot
  /// be followed (problem set when a size does not fit).
  bool labels(const std::string& what, std::string& problem) {
    std::uint8_t version = 0, bytes_per_pixel = 0;
    if (!read(version) || version != 1 || !read(bytes_per_pixel)) return false;
    // MRPT stores the bit fields in the next integer size up: 3 in 4 bytes, 5 to 7 in 8.
    if (bytes_per_pixel == 0 || bytes_per_pixel > 8) return false;  // MRPT refuses it
    bytes_per_pixel = bytes_per_pixel <= 2 ? bytes_per_pixel : bytes_per_pixel <= 4 ? 4 : 8;
    if (!grid(what, bytes_per_pixel, "pixels", problem)) return false;
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

  /// A string or any length-prefixed bytes (uint32 length, bytes). False when it cannot be followed
  /// (problem set when too long).
  bool string(const std::string& what, std::string& problem) {
    std::uint32_t n = 0;
    if (!read(n)) return false;
    if (n > left()) {
      problem = what + " claims " + bytes(n) + " but " + bytes(left()) + " remain in the stream";
      return false;
    }
    return skip(n);
  }

  /// A mrpt::img::CImage object of any version MRPT 2.5 reads: 0 (raw pixels), 1 (JPEG), 2 to 9
  /// (an external-storage flag from 6; grey: sizes, byte count, a pixel depth from 9, a zip flag
  /// from 5; colour: JPEG, or from 7 sizes and a JPEG or, the sizes negated, raw BGR) and 100 (an
  /// image that only names its file). False when it cannot be followed (problem set when a size
  /// does not fit or the version is not one MRPT reads).
  bool image(const std::string& what, std::string& problem) {
    std::string name;
    std::uint8_t version = 0;
    bool old = false;
    if (!header(name, version, old)) return false;
    if (version > 9 && version != 100) return unknownVersion(what, "CImage", version, problem);
    if (version == 0) return rawImage(what, problem) && endFlag(old);
    if (version == 1) return jpeg(what, problem) && endFlag(old);
    std::uint8_t external = 0, colour = 0;
    if ((version >= 6 && !flag(what + " external-storage flag", external, problem))) return false;
    if (version == 100) return (!external || string(what + " file name", problem)) && endFlag(old);
    if (external) return string(what + " file name", problem) && endFlag(old);
    if (!read(colour)) return false;
    if (!colour) return greyImage(what, version, problem) && endFlag(old);
    if (version < 7) return jpeg(what, problem) && endFlag(old);
    std::int32_t width = 1, height = 1;
    if (!read(width) || !read(height)) return false;
    if (width >= 1 && height >= 1) return jpeg(what, problem) && endFlag(old);
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

  /// A version 0 image: width, height, channels (uint32), origin (uint8), byte count (uint32) and
  /// the bytes. MRPT allocates width x height x channels and reads the byte count into it, so a
  /// count above that size would overrun the image: refused with the sizes that do not fit.
  bool rawImage(const std::string& what, std::string& problem) {
    std::uint32_t width = 0, height = 0, channels = 0, count = 0;
    std::uint8_t origin = 0;
    if (!read(width) || !read(height) || !read(channels) || !read(origin) || !read(count)) return false;
    const std::uint64_t size = std::uint64_t{width} * height * std::max<std::uint32_t>(channels, 1);
    if (size > left() || count > size) {
      problem = what + " of " + std::to_string(width) + " x " + std::to_string(height) + " x " +
                std::to_string(channels) + " bytes (" + bytes(count) + " stored) does not fit the " + bytes(left()) +
                " that remain in the stream";
      return false;
    }
    return skip(count);
  }

  /// A JPEG: byte count (uint32) and bytes, laid out as a string (the JPEG's own header: OpenCV's).
  bool jpeg(const std::string& what, std::string& problem) { return string(what + " (JPEG)", problem); }

  /// A grey image of versions 2 to 9: width, height, origin, byte count (int32), a pixel depth
  /// (int32, version 9), whether it is zipped (version 5 on; version 3 always, version 4 above
  /// 16 KiB: MRPT refuses zipped images) and the bytes. MRPT allocates the pixels from the sizes
  /// and the depth before it checks the byte count.
  bool greyImage(const std::string& what, std::uint8_t version, std::string& problem) {
    std::int32_t width = 0, height = 0, origin = 0, count = 0, depth = 0;
    if (!read(width) || !read(height) || !read(origin) || !read(count) || (version >= 9 && !read(depth))) return false;
    // OpenCV depths 8U, 8S, 16U, 16S, 32S, 32F, 64F, 16F.
    constexpr std::uint64_t kDepthBytes[] = {1, 1, 2, 2, 4, 4, 8, 2};
    const std::uint64_t pixels = width < 0 || height < 0 ? 0 : std::uint64_t(width) * std::uint64_t(height);
    const std::uint64_t depth_bytes = depth >= 0 && depth < 8 ? kDepthBytes[depth] : 8;
    if (width < 0 || height < 0 || count < 0 || pixels * depth_bytes > left() || std::uint64_t(count) > left()) {
      problem = what + " of " + std::to_string(width) + " x " + std::to_string(height) + " pixels (" +
                bytes(std::uint64_t(std::max(count, 0))) + ") needs more than the " + bytes(left()) +
                " that remain in the stream";
      return false;
    }
    std::uint8_t zip = version == 3 || (version == 4 && count > 16 * 1024);
    if (version >= 5 && !read(zip)) return false;
    if (zip) return false;  // MRPT refuses it
    return skip(std::uint64_t(count));
  }

  /// A mrpt::img::TCamera object of any version MRPT 2.5 reads (0 to 6): focal length and five
  /// distortion doubles, three more from version 3; before version 4 the intrinsics as a 3 x 3
  /// CMatrixD object, from 4 four doubles; in version 0 a 1 x 5 CMatrixD object; image size
  /// (2 x uint32) from 2; camera name from 5; distortion model (uint8) from 6. False when it
  /// cannot be followed.
  bool camera(const std::string& what, std::string& problem) {
    std::string name;
    std::uint8_t version = 0;
    bool old = false;
    if (!header(name, version, old)) return false;
    if (version > 6) return unknownVersion(what, "TCamera", version, problem);
    if (!skip((version >= 3 ? 9 : 6) * sizeof(double))) return false;
    if (version < 4 ? !matrix(what + " intrinsics", sizeof(double), problem) : !skip(4 * sizeof(double))) return false;
    if (version == 0 && !matrix(what + " distortion", sizeof(double), problem)) return false;
    if (version >= 2 && !skip(2 * sizeof(std::uint32_t))) return false;
    if (version >= 5 && !string(what + " camera name", problem)) return false;
    return skip(version >= 6 ? 1 : 0) && endFlag(old);
  }
};

}  // namespace gasp::detail
