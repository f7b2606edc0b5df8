#include "gasp/pipeline/step_extrapolation.h"

#include <algorithm>
#include <cmath>

namespace gasp {

Isometry3 stepPower(const Isometry3& step, const Eigen::Vector3d& centre, double s) {
  const Eigen::AngleAxisd rotation(step.linear());
  Isometry3 out = Isometry3::Identity();
  out.linear() = Eigen::AngleAxisd(s * rotation.angle(), rotation.axis()).toRotationMatrix();
  const Eigen::Vector3d displacement = step * centre - centre;
  out.translation() = centre - out.linear() * centre + s * displacement;
  return out;
}

StepExtrapolation extrapolateSteps(const Isometry3& older, const Isometry3& newer, const std::vector<Eigen::Vector3d>& points,
                                   double max_factor, double min_cosine) {
  StepExtrapolation out;
  if (!(max_factor > 0.0) || points.empty() || !older.matrix().allFinite() || !newer.matrix().allFinite()) return out;
  double aa = 0, bb = 0, ab = 0;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& x : points) {
    const Eigen::Vector3d a = older * x - x, b = newer * x - x;
    aa += a.squaredNorm();
    bb += b.squaredNorm();
    ab += a.dot(b);
    centre += x;
  }
  if (!(aa > 0.0) || !(bb > 0.0) || !std::isfinite(aa + bb + ab) || !centre.allFinite()) return out;
  centre /= static_cast<double>(points.size());
  out.cosine = ab / std::sqrt(aa * bb);
  out.ratio = std::sqrt(bb / aa);
  if (!(out.cosine >= min_cosine) || !(out.ratio < 1.0)) return out;
  out.factor = std::min(max_factor, out.ratio / (1.0 - out.ratio));
  out.jump = stepPower(newer, centre, out.factor);
  return out;
}

}  // namespace gasp
