#pragma once
/// \file rgbd_frame_bytes.h A frame of a sequence (rgbd_frame.h) as bytes and back, exactly: for
/// a frame read in one process of a job and kept by another (a keyframe for the map outputs).
#include <string>
#include <string_view>

#include "gasp/rawlog/rgbd_frame.h"

namespace gasp {

std::string rgbdFrameBytes(const RgbdFrame& frame);

/// The frame written by rgbdFrameBytes(). Throws gasp::Error saying what is wrong for other bytes.
RgbdFrame rgbdFrameFromBytes(std::string_view bytes);

}  // namespace gasp
