#pragma once
/// \file tracked_frame_bytes.h A tracked frame (odometry.h's TrackedFrame) as bytes and back,
/// exactly: the frame's record, its constraint and its keyframe view (view_bytes.h), for a
/// session tracked in one process of a job and replayed in another.
#include <string>
#include <string_view>

#include "gasp/odometry/odometry.h"

namespace gasp {

std::string trackedFrameBytes(const TrackedFrame& tracked);

/// The frame written by trackedFrameBytes(); its keyframe view as viewFromBytes() reads it with
/// `superpixels` and `returns`. Throws gasp::Error saying what is wrong for other bytes.
TrackedFrame trackedFrameFromBytes(std::string_view bytes, const SuperpixelParams& superpixels,
                                   const ReturnsRefineParams& returns = {});

}  // namespace gasp
