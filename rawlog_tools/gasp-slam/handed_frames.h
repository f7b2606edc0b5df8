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

inline std::string handedFrameBytes(const TrackedFrame& tracked, const RgbdFrame* keyframe) {
  ByteWriter w;
  w.putString(trackedFrameBytes(tracked));
  w.putFlag(keyframe != nullptr);
  if (keyframe) w.putString(rgbdFrameBytes(*keyframe));
  return w.take();
}

inline HandedFrame handedFrameFromBytes(std::string_view bytes, const SlamParams& params) {
  ByteReader r(bytes, "a tracked frame from another rank");
  HandedFrame h;
  h.tracked = trackedFrameFromBytes(r.getString("the frame"), params.odometry.pair.segment, params.odometry.pair.returns);
  if (r.getFlag("the keyframe's flag")) h.keyframe = rgbdFrameFromBytes(r.getString("the keyframe"));
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
  w.putFlag(e.threw);
  w.putFlag(e.reached);
  w.putFlag(e.end.complete);
  w.putString(e.end.error);
  w.putSize(e.end.frames);
  return w.take();
}

inline HandedEnd handedEndFromBytes(std::string_view bytes) {
  ByteReader r(bytes, "a session's end from another rank");
  HandedEnd e;
  e.threw = r.getFlag("its error's flag");
  e.reached = r.getFlag("its first frame's flag");
  e.end.complete = r.getFlag("its end");
  e.end.error = r.getString("its error");
  e.end.frames = r.getSize(0, "its frames");
  r.expectEnd();
  return e;
}

}  // namespace gasp::tools
