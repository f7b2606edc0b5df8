#include "gasp/graphslam/scan_selection.h"

#include <mrpt/obs/CActionRobotMovement3D.h>

namespace gasp::graphslam {

void SkippedMotion::add(const mrpt::obs::CActionCollection::Ptr& actions) {
  mrpt::poses::CPose3DPDFGaussian move;
  if (!actions || actions->size() == 0 || !actions->getFirstMovementEstimation(move)) return;
  if (motion_) *motion_ += move;
  else motion_ = move;
}

mrpt::obs::CActionCollection::Ptr SkippedMotion::prepend(const mrpt::obs::CActionCollection::Ptr& actions) {
  if (!motion_) return actions;
  mrpt::obs::CActionRobotMovement3D merged;
  merged.poseChange = *motion_;
  mrpt::poses::CPose3DPDFGaussian own;
  if (actions && actions->size() > 0) {
    merged.timestamp = actions->get(0)->timestamp;
    if (actions->getFirstMovementEstimation(own)) merged.poseChange += own;
  }
  motion_.reset();
  auto result = std::make_shared<mrpt::obs::CActionCollection>();
  result->insert(merged);
  return result;
}

}  // namespace gasp::graphslam
