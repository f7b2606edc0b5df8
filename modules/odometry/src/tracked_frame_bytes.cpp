#include "gasp/odometry/tracked_frame_bytes.h"

#include <cstdint>
#include <utility>

#include "gasp/core/byte_stream.h"
#include "gasp/pipeline/view_bytes.h"

namespace gasp {

std::string trackedFrameBytes(const TrackedFrame& t) {
  ByteWriter w;
  w.writeHeader("GTF1");
  const OdometryFrame& f = t.frame;
  w.putSize(f.index);
  w.putSize(f.session);
  w.put(f.timestamp);
  w.putPose(f.T_world_camera);
  w.putFlag(f.tracked);
  w.putFlag(f.keyframe);
  w.putSize(f.reference);
  w.putString(f.reason);
  w.put(static_cast<std::int32_t>(f.patches));
  w.put(static_cast<std::int32_t>(f.inliers));
  w.putFlag(f.scene_change);
  w.putFlag(f.partial);
  w.put(static_cast<std::int32_t>(f.free_directions));
  w.putFlag(f.tracking_path);
  w.putFlag(f.deskewed);
  w.put(f.segmentation_ms);
  w.put(f.registration_ms);
  w.putFlag(t.constraint.has_value());
  if (const auto& c = t.constraint) {
    w.putSize(c->from);
    w.putSize(c->to);
    w.putPose(c->T_from_to);
    w.putMatrix(c->information);
    w.put(static_cast<std::int32_t>(c->inliers));
    w.putFlag(c->loop_closure);
    w.putFlag(c->scene_change);
    w.put(static_cast<std::int32_t>(c->free_directions));
  }
  w.putFlag(t.keyframe_view.has_value());
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
  f.tracked = r.getFlag("the frame");
  f.keyframe = r.getFlag("the frame");
  f.reference = r.getSize(0, "the frame");
  f.reason = r.getString("the frame's reason");
  f.patches = r.get<std::int32_t>("the frame");
  f.inliers = r.get<std::int32_t>("the frame");
  f.scene_change = r.getFlag("the frame");
  f.partial = r.getFlag("the frame");
  f.free_directions = r.get<std::int32_t>("the frame");
  f.tracking_path = r.getFlag("the frame");
  f.deskewed = r.getFlag("the frame");
  f.segmentation_ms = r.get<double>("the frame");
  f.registration_ms = r.get<double>("the frame");
  if (r.getFlag("the constraint")) {
    PoseConstraint c;
    c.from = r.getSize(0, "the constraint");
    c.to = r.getSize(0, "the constraint");
    c.T_from_to = r.getPose("the constraint's pose");
    c.information = r.getMatrix<Matrix6d>("the constraint's information");
    c.inliers = r.get<std::int32_t>("the constraint");
    c.loop_closure = r.getFlag("the constraint");
    c.scene_change = r.getFlag("the constraint");
    c.free_directions = r.get<std::int32_t>("the constraint");
    t.constraint = std::move(c);
  }
  if (r.getFlag("the keyframe view")) t.keyframe_view = viewFromBytes(r.getString("the keyframe view"), superpixels, returns);
  r.expectEnd();
  return t;
}

}  // namespace gasp
