#include "gasp/odometry/tracked_frame_bytes.h"

#include <cstdint>
#include <utility>

#include "gasp/core/byte_stream.h"
#include "gasp/pipeline/view_bytes.h"

namespace gasp {

namespace {

void putFlag(ByteWriter& w, bool b) { w.put(static_cast<std::uint8_t>(b ? 1 : 0)); }
bool getFlag(ByteReader& r, const char* what) {
  const auto b = r.get<std::uint8_t>(what);
  if (b > 1) r.fail(std::string(what) + ": a flag neither 0 nor 1");
  return b == 1;
}

}  // namespace

std::string trackedFrameBytes(const TrackedFrame& t) {
  ByteWriter w;
  w.writeHeader("GTF1");
  const OdometryFrame& f = t.frame;
  w.putSize(f.index);
  w.putSize(f.session);
  w.put(f.timestamp);
  w.putPose(f.T_world_camera);
  putFlag(w, f.tracked);
  putFlag(w, f.keyframe);
  w.putSize(f.reference);
  w.putString(f.reason);
  w.put(static_cast<std::int32_t>(f.patches));
  w.put(static_cast<std::int32_t>(f.inliers));
  putFlag(w, f.scene_change);
  putFlag(w, f.partial);
  w.put(static_cast<std::int32_t>(f.free_directions));
  putFlag(w, f.tracking_path);
  putFlag(w, f.deskewed);
  w.put(f.segmentation_ms);
  w.put(f.registration_ms);
  putFlag(w, t.constraint.has_value());
  if (const auto& c = t.constraint) {
    w.putSize(c->from);
    w.putSize(c->to);
    w.putPose(c->T_from_to);
    w.putMatrix(c->information);
    w.put(static_cast<std::int32_t>(c->inliers));
    putFlag(w, c->loop_closure);
    putFlag(w, c->scene_change);
    w.put(static_cast<std::int32_t>(c->free_directions));
  }
  putFlag(w, t.keyframe_view.has_value());
  if (t.keyframe_view) w.putString(viewBytes(*t.keyframe_view));
  return w.take();
}

TrackedFrame trackedFrameFromBytes(std::string_view bytes, const SuperpixelParams& superpixels,
                                   const ReturnsRefineParams& returns) {
  ByteReader r(bytes, "tracked frame bytes");
  r.readHeader("GTF1");
  TrackedFrame t;
  OdometryFrame& f = t.frame;
  f.index = r.getSize(0, "the frame");
  f.session = r.getSize(0, "the frame");
  f.timestamp = r.get<double>("the frame");
  f.T_world_camera = r.getPose("the frame's pose");
  f.tracked = getFlag(r, "the frame");
  f.keyframe = getFlag(r, "the frame");
  f.reference = r.getSize(0, "the frame");
  f.reason = r.getString("the frame's reason");
  f.patches = r.get<std::int32_t>("the frame");
  f.inliers = r.get<std::int32_t>("the frame");
  f.scene_change = getFlag(r, "the frame");
  f.partial = getFlag(r, "the frame");
  f.free_directions = r.get<std::int32_t>("the frame");
  f.tracking_path = getFlag(r, "the frame");
  f.deskewed = getFlag(r, "the frame");
  f.segmentation_ms = r.get<double>("the frame");
  f.registration_ms = r.get<double>("the frame");
  if (getFlag(r, "the constraint")) {
    PoseConstraint c;
    c.from = r.getSize(0, "the constraint");
    c.to = r.getSize(0, "the constraint");
    c.T_from_to = r.getPose("the constraint's pose");
    c.information = r.getMatrix<Matrix6d>("the constraint's information");
    c.inliers = r.get<std::int32_t>("the constraint");
    c.loop_closure = getFlag(r, "the constraint");
    c.scene_change = getFlag(r, "the constraint");
    c.free_directions = r.get<std::int32_t>("the constraint");
    t.constraint = std::move(c);
  }
  if (getFlag(r, "the keyframe view")) t.keyframe_view = viewFromBytes(r.getString("the keyframe view"), superpixels, returns);
  r.expectEnd();
  return t;
}

}  // namespace gasp
