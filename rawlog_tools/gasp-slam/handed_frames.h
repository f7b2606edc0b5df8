#pragma once
// gasp-slam --mpi: what a rank that tracks a session hands rank 0 (gasp/mpi/registrar_pool.h),
// as bytes: each frame as its odometry tracked it, then how the session ended.
#include <optional>
#include <string>
#include <string_view>

#include "gasp/core/byte_stream.h"
#include "gasp/odometry/tracked_frame_bytes.h"
#include "gasp/rawlog/rgbd_frame_bytes.h"
#include "gasp/slam/slam_params.h"
#include "frames_ahead.h"

namespace gasp::tools {

/// A frame tracked on another rank: its TrackedFrame and, when the map outputs keep keyframes,
/// the keyframe's frame as the map keeps it (depth only).
struct HandedFrame {
  TrackedFrame tracked;
  std::optional<RgbdFrame> keyframe;
};

inline bool getFlag(ByteReader& r, const char* what) {
  const auto b = r.get<std::uint8_t>(what);
  if (b > 1) r.fail(std::string(what) + ": neither 0 nor 1");
  return b == 1;
}

inline std::string handedFrameBytes(const TrackedFrame& tracked, const RgbdFrame* keyframe) {
  ByteWriter w;
  w.putString(trackedFrameBytes(tracked));
  w.put(static_cast<std::uint8_t>(keyframe ? 1 : 0));
  if (keyframe) w.putString(rgbdFrameBytes(*keyframe));
  return w.take();
}

inline HandedFrame handedFrameFromBytes(std::string_view bytes, const SlamParams& params) {
  ByteReader r(bytes, "a tracked frame from another rank");
  HandedFrame h;
  h.tracked = trackedFrameFromBytes(r.getString("the frame"), params.odometry.pair.segment, params.odometry.pair.returns);
  if (getFlag(r, "the keyframe's flag")) h.keyframe = rgbdFrameFromBytes(r.getString("the keyframe"));
  r.expectEnd();
  return h;
}

/// How a session tracked on another rank ended: as forEachFrameWithViewAhead() returned (`end`),
/// or with the error it threw (`threw`; `end.error` is its message). `reached`: a frame of it got
/// past the mounting check, so that one process would have started the session in the graph
/// (made the graph, for the first) even when that frame's tracking threw.
struct HandedEnd {
  bool threw = false;
  bool reached = false;
  SequenceEnd end;
};

inline std::string handedEndBytes(const HandedEnd& e) {
  ByteWriter w;
  w.put(static_cast<std::uint8_t>(e.threw ? 1 : 0));
  w.put(static_cast<std::uint8_t>(e.reached ? 1 : 0));
  w.put(static_cast<std::uint8_t>(e.end.complete ? 1 : 0));
  w.putString(e.end.error);
  w.putSize(e.end.frames);
  return w.take();
}

inline HandedEnd handedEndFromBytes(std::string_view bytes) {
  ByteReader r(bytes, "a session's end from another rank");
  HandedEnd e;
  e.threw = getFlag(r, "its error's flag");
  e.reached = getFlag(r, "its first frame's flag");
  e.end.complete = getFlag(r, "its end");
  e.end.error = r.getString("its error");
  e.end.frames = r.getSize(0, "its frames");
  r.expectEnd();
  return e;
}

}  // namespace gasp::tools
