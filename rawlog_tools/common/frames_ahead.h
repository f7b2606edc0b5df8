#pragma once
/// \file frames_ahead.h The frame loop of gasp-odometry and gasp-slam: each frame of a sequence
/// in order, the next one read and segmented (gasp::ViewAhead) while the current one is added.
#include <cstddef>
#include <optional>
#include <string>
#include <utility>

#include "gasp/core/error.h"
#include "gasp/odometry/view_ahead.h"
#include "gasp/rawlog/depth_sequence.h"

namespace gasp::tools {

/// How the input ended: every frame read, or an error after some frames (a truncated rawlog, an
/// image that cannot be read), whose frames before it were all added.
struct SequenceEnd {
  bool complete = true;
  std::string error;       ///< the input's error (gasp::Error's message) when not complete
  std::size_t frames = 0;  ///< frames added
};

/// Calls `add(frame, segmented)` for every frame of `sequence`, in order; `segmented` is the
/// frame's view made while the previous call ran (empty when the odometry deskews, see
/// view_ahead.h, or with `sequential`), for DepthOdometry::addFrame() / DepthSlam::addFrame().
/// A frame the sequence cannot read ends the loop after every frame before it was added: the
/// result says so, for the program to write what was computed and call it partial. The first
/// frame failing is an error (thrown), as is any error of `add`.
template <typename Add>
SequenceEnd forEachFrameWithViewAhead(DepthSequence& sequence, const OdometryParams& params, bool sequential, Add&& add) {
  SequenceEnd end;
  ViewAhead ahead(params, !sequential);
  std::optional<RgbdFrame> frame = sequence.next();
  if (frame) ahead.start(frame->depth_m, frame->depth_intrinsics);
  while (frame) {
    std::optional<SegmentedDepth> segmented = ahead.take();
    std::optional<RgbdFrame> next;
    try {
      next = sequence.next();
    } catch (const Error& e) {
      end.complete = false;
      end.error = e.what();
    }
    if (next) ahead.start(next->depth_m, next->depth_intrinsics);
    add(*frame, std::move(segmented));
    ++end.frames;
    frame = std::move(next);
  }
  return end;
}

}  // namespace gasp::tools
