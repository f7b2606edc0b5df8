#include "gasp/mrpt/keyframe_map.h"

#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/obs/CObservationPointCloud.h>
#include <mrpt/obs/CObservationRotatingScan.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPose3DPDFGaussian.h>
#include <mrpt/serialization/CArchive.h>

#include <memory>
#include <string>

#include "gasp/core/depth_image.h"
#include "gasp/core/error.h"
#include "gasp/mrpt/pose_covariance.h"
#include "gasp/rawlog/gz_output_stream.h"
#include "gasp/rawlog/observation_conversion.h"
#include "gasp/rawlog/range_scan.h"

namespace gasp {

namespace {

/// A sweep as it was read: a rotating scan (its range image and layout), or a point cloud when
/// its returns carry their own rays (a cloud or a Velodyne's calibrated points, which MRPT 2.5's
/// rotating scan has no place for). With `with_points`, a 3D range scan of its points
/// (toPointsScan()): MRPT 2.5's points maps insert no rotating scan and place a point cloud at its
/// sensorPose without the robot's pose; GASP finds the layout of the points again. The LiDAR's
/// sensorPose is the frame's mounting.
mrpt::obs::CObservation::Ptr sweepObservation(const RgbdFrame& f, bool with_points) {
  RangeScan scan = *f.sweep;
  scan.T_robot_sensor = f.T_robot_camera;
  if (with_points) return std::make_shared<mrpt::obs::CObservation3DRangeScan>(toPointsScan(scan, f.sensor_label));
  if (!scan.ray.empty())
    return std::make_shared<mrpt::obs::CObservationPointCloud>(toPointCloud(scan, f.sensor_label));
  return std::make_shared<mrpt::obs::CObservationRotatingScan>(toRotatingScan(scan, f.sensor_label));
}

}  // namespace

mrpt::maps::CSimpleMap keyframeSimpleMap(const std::vector<RgbdFrame>& keyframes,
                                         const std::vector<Isometry3>& T_world_camera,
                                         const std::vector<Matrix6>& covariance_world_camera, bool with_points) {
  if (keyframes.size() != T_world_camera.size())
    throw Error("keyframe map: " + std::to_string(keyframes.size()) + " keyframes but " +
                std::to_string(T_world_camera.size()) + " poses");
  if (!covariance_world_camera.empty() && covariance_world_camera.size() != keyframes.size())
    throw Error("keyframe map: " + std::to_string(keyframes.size()) + " keyframes but " +
                std::to_string(covariance_world_camera.size()) + " covariances");
  mrpt::maps::CSimpleMap map;
  for (std::size_t i = 0; i < keyframes.size(); ++i) {
    const RgbdFrame& f = keyframes[i];
    auto gaussian = mrpt::poses::CPose3DPDFGaussian::Create();
    const Isometry3 T_world_robot = T_world_camera[i] * f.T_robot_camera.inverse();
    if (covariance_world_camera.empty())
      gaussian->mean = toCPose3D(T_world_robot);
    else
      *gaussian = poseWithCovariance(T_world_robot, covariance_world_camera[i]);
    const mrpt::poses::CPose3DPDF::Ptr pose = gaussian;
    auto sf = mrpt::obs::CSensoryFrame::Create();
    if (f.isSweep()) {
      sf->insert(sweepObservation(f, with_points));
    } else {
      const mrpt::obs::CObservation3DRangeScan::Ptr obs = observationFromFrame(f);
      if (with_points) storePoints3D(*obs);
      sf->insert(obs);
    }
    map.insert(pose, sf);
  }
  return map;
}

RgbdFrame withViewDepth(RgbdFrame frame, const DepthView& view) {
  const CameraIntrinsics& K = view.projection.pinhole();
  if (view.depth_m.type() != CV_32FC1 || view.depth_m.cols != K.width || view.depth_m.rows != K.height)
    throw Error("keyframe map: the view's depth is not a CV_32FC1 image of its intrinsics' size (" +
                std::to_string(K.width) + "x" + std::to_string(K.height) + ")");
  const bool had_raw = frame.hasRawDepth();
  frame.depth_m = view.depth_m.clone();
  frame.depth_intrinsics = K;
  frame.depth_raw = had_raw ? depthToRaw(frame.depth_m, frame.depth_units_per_metre) : cv::Mat();
  if (!had_raw) frame.depth_units_per_metre = 0.0;
  frame.rgb.release();
  return frame;
}

void saveSimpleMap(const mrpt::maps::CSimpleMap& map, const std::string& path) {
  OutputFile file(path, "simple map");
  saveSimpleMap(map, file);
}

void saveSimpleMap(const mrpt::maps::CSimpleMap& map, OutputFile& file) {
  GzOutputStream stream(file, 1);  // gzip, as CSimpleMap::saveToFile() writes it
  try {
    mrpt::serialization::archiveFrom(stream) << map;
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    throw Error("cannot write simple map '" + file.path() + "': " + exceptionMessage(e));
  }
  stream.finish();
}

}  // namespace gasp
