#pragma once
/// \file rawlog_reader.h Reads the RGB-D (CObservation3DRangeScan) observations and the rotating
/// LiDARs' sweeps (CObservationRotatingScan, CObservationVelodyneScan) of an MRPT rawlog.
#include <cstddef>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "gasp/rawlog/rawlog_format.h"
#include "gasp/rawlog/rgbd_frame.h"

namespace gasp {

/// Streams the CObservation3DRangeScan observations of a rawlog in file order, converted to
/// RgbdFrame (see frameFromObservation()), and, when asked, its LiDAR sweeps as frames with `sweep`
/// set (rangeScanFrom(), range_scan.h; the observation's sensorPose as T_robot_camera). Reads format #1 (actions / sensory frames) and #2
/// (observations), gzip-compressed or plain. Other observation types and actions are skipped and
/// counted. Externally stored range images and intensity images are resolved against
/// findRawlogImagesDirectory(path) ("<name>_Images" beside the rawlog), whatever the working
/// directory.
///
/// Errors (gasp::Error, naming the file): those of RawlogObjects (missing or empty file, not a
/// rawlog, a truncated or corrupt stream, a class no loaded library registers); a rawlog without
/// any CObservation3DRangeScan or sweep (reported by next() at the end, listing the types found); a
/// scan without range image; a sweep GASP cannot read (a model whose elevations it does not know).
class RawlogReader {
 public:
  /// Opens the rawlog and reads its first object (so that empty or garbage files fail here).
  /// `read_sweeps`: return LiDAR sweeps too (else they are skipped and counted as other types);
  /// `sweep_label` (when not empty): only the sweeps of that sensor (the others are not converted).
  explicit RawlogReader(const std::string& path, bool read_sweeps = false, std::string sweep_label = {});
  ~RawlogReader();
  RawlogReader(RawlogReader&&) noexcept;
  RawlogReader& operator=(RawlogReader&&) noexcept;

  /// The next 3D range scan or sweep as a frame, or nullopt at the end of the file.
  std::optional<RgbdFrame> next();

  const std::string& path() const { return path_; }
  /// Folder against which relative external files are resolved.
  const std::string& imagesDirectory() const { return images_dir_; }
  /// The layout seen so far (decided by the first object).
  RawlogFormat format() const { return format_; }
  /// Number of 3D range scans and sweeps returned so far.
  std::size_t scansRead() const { return scans_read_; }
  /// Class names and counts of the other objects met so far (observations of other types,
  /// CActionCollection, ...).
  const std::map<std::string, std::size_t>& skipped() const { return skipped_; }
  /// "3 x CObservationOdometry, 1 x CObservationIMU" (or "nothing").
  std::string skippedSummary() const;

 private:
  struct Impl;
  std::string path_;
  std::string images_dir_;
  bool read_sweeps_ = false;
  std::string sweep_label_;
  RawlogFormat format_ = RawlogFormat::Observations;
  std::size_t scans_read_ = 0;
  std::map<std::string, std::size_t> skipped_;
  std::unique_ptr<Impl> impl_;
};

/// All 3D range scans of a rawlog (RawlogReader::next() until the end).
std::vector<RgbdFrame> readRawlogFrames(const std::string& path);

}  // namespace gasp
