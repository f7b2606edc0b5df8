#pragma once
/// \file depth_sequence.h The depth frames of a TUM RGB-D folder or of an MRPT rawlog, in order, as
/// the sequence programs (gasp-odometry, gasp-slam) read them: from the `first`-th, every
/// `every`-th, at most `max_frames`.
#include <cstddef>
#include <memory>
#include <optional>
#include <string>

#include "gasp/core/tum_trajectory.h"
#include "gasp/rawlog/rgbd_frame.h"

namespace gasp {

struct DepthSequenceOptions {
  std::string tum_dir;       ///< a TUM folder (frames in depth.txt order) ...
  std::string rawlog_path;   ///< ... or an MRPT rawlog (its CObservation3DRangeScan in file order)
  /// rawlog: its rotating LiDARs' sweeps are frames too (RgbdFrame::sweep). One kind of frame per
  /// sequence, its first scan's: without sensor_label, a rawlog that starts with depth images reads
  /// those (its sweeps skipped, as without this), and one that starts with sweeps and holds depth
  /// images too is an error asking for the label.
  bool sweeps = false;
  std::string sensor_label;  ///< rawlog: only the scans with this sensorLabel (empty: all)
  std::size_t first = 0;     ///< index of the first frame used, among the input's frames
  std::size_t every = 1;     ///< use every N-th frame
  std::size_t max_frames = 0;  ///< at most this many frames (0 = all)
  bool with_rgb = false;       ///< TUM: load the associated rgb image too
  /// TUM: the camera, a preset (fr1, fr2, fr3, ros) or a file (CameraIntrinsics::save's format);
  /// empty: the folder's intrinsics.txt, else a preset guessed from its name, else the ROS default
  /// (TumDataset::Options). A rawlog's scans carry their own.
  std::string intrinsics;
  double depth_units_per_metre = 5000.0;  ///< TUM: raw depth units per metre (TUM: 5000)
  bool undistort = true;                  ///< TUM: resample to the pinhole camera when the intrinsics carry lens distortion
};

class DepthSequence {
 public:
  /// Throws gasp::Error for neither or both inputs, every = 0, a missing or corrupt folder or
  /// rawlog, `first` beyond a TUM folder's frames, or intrinsics that cannot be read.
  explicit DepthSequence(const DepthSequenceOptions& options);
  ~DepthSequence();
  DepthSequence(DepthSequence&&) noexcept;
  DepthSequence& operator=(DepthSequence&&) noexcept;

  /// The next frame used, or nullopt at the end. Throws gasp::Error for a corrupt frame, a rawlog
  /// scan whose sensorPose differs from the first used (one camera only: choose it with
  /// sensor_label) or of another kind (a sweep after depth images or the other way), and, at the
  /// end, when no frame at all was used.
  std::optional<RgbdFrame> next();
  /// The frame the next next() returns, read ahead (same errors), or null at the end: what the
  /// sequence holds (depth images or sweeps) before the programs choose their parameters. When it
  /// throws, the next next() throws the same error (the frame is not skipped silently), then the
  /// input goes on as it would have after that error. framesUsed() counts a peeked frame.
  const RgbdFrame* peek();

  /// Index among the input's frames (counting only the chosen sensor's scans) of the frame the
  /// last next() returned.
  std::size_t inputIndex() const { return input_index_; }
  std::size_t framesUsed() const { return used_; }
  /// The TUM folder's ground truth (empty for a rawlog or a folder without one).
  const Trajectory& groundTruth() const { return ground_truth_; }
  /// Rawlog: the depth camera's (or the LiDAR's) pose on the robot (sensorPose) shared by every frame used
  /// (identity until the first). TUM folder: the identity (gasp-odometry's graphs stay in
  /// optical frames), although each frame carries mrptCameraFromOptical() as T_robot_camera.
  const Isometry3& robotCamera() const { return T_robot_camera_; }
  /// "TUM folder DIR" or "rawlog FILE".
  std::string describe() const;
  /// TUM folder: TumDataset::intrinsicsSummary(); rawlog: each scan's own (its cameraParams, or
  /// a sweep's model).
  std::string intrinsicsSummary() const;
  /// TUM folder: TumDataset::intrinsicsWarning(); rawlog: "".
  std::string intrinsicsWarning() const;

 private:
  struct Impl;
  DepthSequenceOptions options_;
  std::unique_ptr<Impl> impl_;
  Trajectory ground_truth_;
  Isometry3 T_robot_camera_ = Isometry3::Identity();
  std::size_t input_index_ = 0;
  std::size_t used_ = 0;
  bool sweeps_ = false;  ///< the sequence's frames are sweeps (its first scan was one)
  /// The next frame used and its input index, or nullopt at the end (next() without the peek).
  std::optional<RgbdFrame> read(std::size_t& index);
  std::optional<RgbdFrame> peeked_;  ///< peek()'s frame, which next() returns
  std::size_t peeked_index_ = 0;
  bool peeked_end_ = false;  ///< peek() met the end
  std::optional<std::string> peek_error_;  ///< peek()'s error, which the next next() throws again
  bool kind_decided_ = false;  ///< the first scan (of the chosen sensor) was seen: sweeps_ holds its kind
};

}  // namespace gasp
