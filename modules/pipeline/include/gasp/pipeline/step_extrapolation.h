#pragma once
/// \file step_extrapolation.h Extrapolation of a creeping iteration of rigid poses (Besl & McKay,
/// "A Method for Registration of 3-D Shapes", 1992, section IV-C, "accelerated ICP").
///
/// Where only small structures pin a slide along large planes, each dense round moves the pose
/// a little further the same way, and the rounds stop (a step below dense_converged_m) while the
/// pose is still centimetres short. Two successive steps A (older) and B (newer), left-multiplied
/// increments in the target frame, are compared on points x_i (the source patch centroids at the
/// current pose): with the displacements a_i = A x_i - x_i and b_i = B x_i - x_i,
///   cosine = sum a_i . b_i / sqrt(sum |a_i|^2 sum |b_i|^2),   ratio r = sqrt(sum |b_i|^2 / sum |a_i|^2).
/// When the steps point the same way (cosine >= min_cosine) and shrink geometrically, the rest of
/// the iteration sums to B^s with s = r / (1 - r) (the geometric series r + r^2 + ...); s is capped
/// at max_factor. Steps that do not shrink (r >= 1) are not extrapolated: the iteration is then
/// running into its basin, not converging, and a jump there can overshoot. B^s is B taken s
/// times about the points' centre c: rotation by s times B's angle about B's axis through c, and
/// s times the displacement of c.
#include <vector>

#include <Eigen/Core>

#include "gasp/core/pose.h"

namespace gasp {

struct StepExtrapolation {
  double factor = 0.0;   ///< s: 0 = no extrapolation (steps disagree, or no points / no motion)
  double cosine = 0.0;   ///< of the two steps' displacement fields
  double ratio = 0.0;    ///< RMS displacement of the newer step over the older one's
  Isometry3 jump = Isometry3::Identity();  ///< B^s, to be left-multiplied onto the current pose
};

/// `older`, `newer`: successive increments (T_after = step * T_before) in the frame of `points`.
/// Never throws; non-finite input gives factor 0. `max_factor` <= 0 turns it off.
StepExtrapolation extrapolateSteps(const Isometry3& older, const Isometry3& newer, const std::vector<Eigen::Vector3d>& points,
                                   double max_factor, double min_cosine = 0.95);

/// B^s about the centre c (see the file's comment); exact for a rotation about an axis through c
/// and for a translation.
Isometry3 stepPower(const Isometry3& step, const Eigen::Vector3d& centre, double s);

}  // namespace gasp
