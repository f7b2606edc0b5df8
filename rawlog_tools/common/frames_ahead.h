#pragma once
/// \file frames_ahead.h The frame loop of gasp-odometry and gasp-slam: each frame of a sequence
/// in order, the next kFramesAhead frames read and segmented (gasp::ViewAhead) while the current
/// one is added.
#include <cstddef>
#include <deque>
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

/// Frames segmented at once while one is added: a segmentation takes about twice a tracked
/// frame's registration, so two segmentations and the registration keep two cores busy.
inline constexpr std::size_t kFramesAhead = 2;

/// Calls `add(frame, segmented)` for every frame of `sequence`, in order; `segmented` is the
/// frame's view made while earlier calls ran (empty when the odometry deskews, see
/// view_ahead.h, or with `sequential`), for DepthOdometry::addFrame() / DepthSlam::addFrame().
/// A frame the sequence cannot read ends the loop after every frame before it was added: the
/// result says so, for the program to write what was computed and call it partial. The first
/// frame failing is an error (thrown), as is any error of `add`.
template <typename Add>
SequenceEnd forEachFrameWithViewAhead(DepthSequence& sequence, const OdometryParams& params, bool sequential, Add&& add) {
  SequenceEnd end;
  ViewAhead ahead(params, !sequential);
  std::deque<RgbdFrame> frames;  // read, and started in `ahead` in the same order
  const auto started = [&](std::optional<RgbdFrame> f) {
    if (!f) return false;
    if (f->isSweep())
      ahead.start(*f->sweep);
    else
      ahead.start(f->depth_m, f->depth_intrinsics);
    frames.push_back(std::move(*f));
    return true;
  };
  // The next frame, read and started; false at the end of the input or at its error.
  const auto readOne = [&] {
    try {
      return started(sequence.next());
    } catch (const Error& e) {
      end.complete = false;
      end.error = e.what();
      return false;
    }
  };
  bool more = started(sequence.next());
  while (more && frames.size() < kFramesAhead) more = readOne();
  while (!frames.empty()) {
    RgbdFrame frame = std::move(frames.front());
    frames.pop_front();
    if (more) more = readOne();  // read while the frames before it are still being segmented
    std::optional<SegmentedDepth> segmented = ahead.take();
    add(frame, std::move(segmented));
    ++end.frames;
  }
  return end;
}

}  // namespace gasp::tools
