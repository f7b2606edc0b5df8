#include "gasp/rawlog/rgbd_frame_bytes.h"

#include <cstdint>

#include "gasp/core/byte_stream.h"

namespace gasp {

std::string rgbdFrameBytes(const RgbdFrame& f) {
  ByteWriter w;
  w.writeHeader("GRF1");
  w.put(f.timestamp);
  w.putMat(f.depth_m);
  w.putMat(f.depth_raw);
  w.put(f.depth_units_per_metre);
  // Intrinsics only with their image: a sweep has no depth image, a depth-only frame no colour.
  if (!f.depth_m.empty()) w.putIntrinsics(f.depth_intrinsics);
  w.putMat(f.rgb);
  if (!f.rgb.empty()) w.putIntrinsics(f.rgb_intrinsics);
  w.putPose(f.T_depth_rgb);
  w.putPose(f.T_robot_camera);
  w.putString(f.sensor_label);
  w.putFlag(f.sweep.has_value());
  if (f.sweep) w.putScan(*f.sweep);
  return w.take();
}

RgbdFrame rgbdFrameFromBytes(std::string_view bytes) {
  ByteReader r(bytes, "frame bytes");
  r.readHeader("GRF1");
  RgbdFrame f;
  f.timestamp = r.get<double>("the timestamp");
  f.depth_m = r.getMat("the depth", CV_32FC1);
  f.depth_raw = r.getMat("the stored depth", CV_16UC1);
  f.depth_units_per_metre = r.get<double>("the depth's units");
  if (!f.depth_m.empty()) f.depth_intrinsics = r.getIntrinsics("the depth's intrinsics");
  f.rgb = r.getMat("the colour", CV_8UC3);
  if (!f.rgb.empty()) f.rgb_intrinsics = r.getIntrinsics("the colour's intrinsics");
  f.T_depth_rgb = r.getPose("the colour camera's pose");
  f.T_robot_camera = r.getPose("the camera's mounting");
  f.sensor_label = r.getString("the sensor label");
  if (r.getFlag("the sweep")) f.sweep = r.getScan();
  r.expectEnd();
  return f;
}

}  // namespace gasp
