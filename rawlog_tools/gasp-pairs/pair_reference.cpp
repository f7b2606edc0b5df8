#include "pair_reference.h"

#include <Eigen/Geometry>

#include "gasp/core/camera_roll.h"

namespace gasp::pairs {

PairReference::PairReference(const TumDataset& ds, double offset_s, const Eigen::Vector3d& frame_rotation_rad,
                             int roll_target_deg)
    : ds_(ds), offset_s_(offset_s), T_rolled_target_(turnRotation(roll_target_deg)) {
  const Eigen::Vector3d& r = frame_rotation_rad;
  if (r.norm() > 0) Q_inv_.linear() = Eigen::AngleAxisd(r.norm(), r.normalized()).toRotationMatrix().transpose();
}

std::optional<Isometry3> PairReference::turnedBack(std::optional<Isometry3> T) const {
  if (T) *T = *T * Q_inv_;
  return T;
}

std::optional<Isometry3> PairReference::frame(std::size_t i) const {
  return turnedBack(ds_.groundTruthOf(i, offset_s_));
}

std::optional<Isometry3> PairReference::at(double t) const { return turnedBack(ds_.groundTruthAt(t + offset_s_)); }

std::optional<Isometry3> PairReference::pair(std::size_t i, std::size_t j) const {
  const auto Ti = frame(i), Tj = frame(j);
  if (!Ti || !Tj) return std::nullopt;
  return Isometry3(T_rolled_target_ * relativePose(*Tj, *Ti));
}

}  // namespace gasp::pairs
