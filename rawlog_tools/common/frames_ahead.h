#pragma once
/// \file frames_ahead.h The frame loop of gasp-odometry and gasp-slam: each frame of a sequence
/// in order, the next one read and segmented (gasp::ViewAhead) while the current one is added.
#include <optional>
#include <utility>

#include "gasp/odometry/view_ahead.h"
#include "gasp/rawlog/depth_sequence.h"

namespace gasp::tools {

/// Calls `add(frame, segmented)` for every frame of `sequence`, in order; `segmented` is the
/// frame's view made while the previous call ran (empty when the odometry deskews, see
/// view_ahead.h, or with `sequential`), for DepthOdometry::addFrame() / DepthSlam::addFrame().
/// The next frame is read before `add` runs, so a frame the sequence cannot read ends the loop
/// (its error thrown) before the frame before it is added.
template <typename Add>
void forEachFrameWithViewAhead(DepthSequence& sequence, const OdometryParams& params, bool sequential, Add&& add) {
  ViewAhead ahead(params, !sequential);
  std::optional<RgbdFrame> frame = sequence.next();
  if (frame) ahead.start(frame->depth_m, frame->depth_intrinsics);
  while (frame) {
    std::optional<SegmentedDepth> segmented = ahead.take();
    std::optional<RgbdFrame> next = sequence.next();
    if (next) ahead.start(next->depth_m, next->depth_intrinsics);
    add(*frame, std::move(segmented));
    frame = std::move(next);
  }
}

}  // namespace gasp::tools
