#pragma once
/// \file rawlog_writer.h Writes RGB-D frames as an MRPT rawlog of CObservation3DRangeScan, and
/// LiDAR sweeps as CObservationRotatingScan.
#include <cstddef>
#include <memory>
#include <string>

#include "gasp/rawlog/rawlog_format.h"
#include "gasp/core/range_scan.h"
#include "gasp/rawlog/rgbd_frame.h"

namespace mrpt::obs {
class CObservation;
}

namespace gasp {

struct RawlogWriterOptions {
  /// #2 (default): a stream of observations; #1: each observation in its own CSensoryFrame,
  /// preceded by an empty CActionCollection.
  RawlogFormat format = RawlogFormat::Observations;
  /// Store range images (MRPT's gz-compressed .bin matrix files) and rgb images (PNG) in
  /// "<name>_Images" beside the rawlog, referenced by relative file names, instead of inline.
  bool external_storage = false;
  /// gzip level of the rawlog itself (0 = plain, 1..9); MRPT reads both.
  int compress_level = 1;
  /// Store each depth image's 3D points in its observation too (MRPT's unprojection, in the
  /// camera's frame; inline, also with external_storage: about 3.7 MB per 640x480 frame before
  /// compression), which MRPT's points maps need to insert a scan (what `rawlog-edit
  /// --generate-3d-pointclouds` adds to a rawlog); a sweep as a 3D range scan of its points
  /// (toPointsScan()) instead of a rotating scan. GASP reads them as without.
  bool points = false;
};

/// Writes a rawlog, whole or not at all: the frames go to a temporary file in the rawlog's folder
/// (gasp/core/output_file.h) that close() renames to `path`, so a run that fails or is killed
/// half-way leaves an existing rawlog at `path` as it was, never a shorter one that reads as
/// complete, and nothing beside it. The destructor closes too, except while an exception unwinds
/// the stack: then (as with discard()) the temporary file is dropped. A `path` that is a symbolic
/// link keeps it (the file it names is replaced); a device, FIFO or folder is refused. External
/// images are written in place.
class RawlogWriter {
 public:
  /// Opens the temporary file, creating the rawlog's folder if needed; with external storage also
  /// creates "<name>_Images".
  /// Throws gasp::Error when the file or folder cannot be created.
  explicit RawlogWriter(const std::string& path, const RawlogWriterOptions& options = {});
  ~RawlogWriter();
  RawlogWriter(RawlogWriter&&) noexcept;
  RawlogWriter& operator=(RawlogWriter&&) noexcept;

  /// Converts the frame (observationFromFrame()) and appends it. Throws gasp::Error.
  void write(const RgbdFrame& frame);
  /// Appends a sweep as MRPT 2.5's CObservationRotatingScan (toRotatingScan(), range_scan.h; its
  /// ranges inline, whatever external_storage says). Throws gasp::Error.
  void write(const RangeScan& sweep, const std::string& sensor_label);
  /// Appends a sweep as a CObservationPointCloud (toPointCloud(), range_scan.h). Throws gasp::Error.
  void writePointCloud(const RangeScan& sweep, const std::string& sensor_label);
  /// Ends the stream, checks every write, and renames the file to path() (also done by the
  /// destructor, unless an exception is unwinding, where errors cannot be reported: call it).
  /// Throws gasp::Error naming the file when a write or the rename failed; no-op once closed.
  void close();
  /// Drops what was written: path() is left as it was. No-op once closed.
  void discard();

  std::size_t framesWritten() const { return frames_written_; }
  const std::string& path() const { return path_; }
  /// "<name>_Images" (only created with external storage).
  const std::string& imagesDirectory() const { return images_dir_; }

 private:
  struct Impl;
  std::string path_;
  std::string images_dir_;
  int uncaught_at_construction_ = 0;  ///< std::uncaught_exceptions() then
  RawlogWriterOptions options_;
  std::size_t frames_written_ = 0;
  void checkOpen() const;  ///< throws when closed
  void append(const std::shared_ptr<mrpt::obs::CObservation>& observation);
  std::unique_ptr<Impl> impl_;
};

}  // namespace gasp
