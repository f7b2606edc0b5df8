#pragma once
/// \file pair_reference.h gasp-pairs: the reference (ground truth) each pair is scored against.
/// A frame's pose is the folder's ground truth at the depth stamp + `offset_s` (the frame's own
/// association at offset 0; --gt-offset); with --gt-frame-rotation r the reference's camera frame
/// is taken as the depth camera's turned by Q = exp(r), so the depth camera's pose is
/// T_world_ref Q^-1; with --roll-target the target's camera is rolled about its optical axis.
#include <Eigen/Core>

#include <cstddef>
#include <optional>

#include "gasp/core/pose.h"
#include "gasp/core/tum_dataset.h"

namespace gasp::pairs {

class PairReference {
 public:
  /// `frame_rotation_rad`: r of Q = exp(r) (zero: none); `roll_target_deg`: 0, 90, 180 or 270.
  PairReference(const TumDataset& ds, double offset_s, const Eigen::Vector3d& frame_rotation_rad,
                int roll_target_deg);

  /// T_world_camera of frame i, or none without ground truth near its stamp.
  std::optional<Isometry3> frame(std::size_t i) const;
  /// T_world_camera at time t (+ the offset), or none.
  std::optional<Isometry3> at(double t) const;
  /// The reference T_target_source of the pair (i -> j), j's camera rolled; none unless both
  /// frames have ground truth.
  std::optional<Isometry3> pair(std::size_t i, std::size_t j) const;

 private:
  std::optional<Isometry3> turnedBack(std::optional<Isometry3> T) const;

  const TumDataset& ds_;
  double offset_s_;
  Isometry3 Q_inv_ = Isometry3::Identity();
  Isometry3 T_rolled_target_;
};

}  // namespace gasp::pairs
