#pragma once
/// \file keyframe_map.h A map built offline by GASP's SLAM as MRPT consumes it: the keyframes'
/// scans at their optimised poses in an mrpt::maps::CSimpleMap, from which MRPT's own tools
/// build metric maps (observations2map: point maps, octomaps, occupancy grids).
#include <mrpt/maps/CSimpleMap.h>

#include <string>
#include <vector>

#include "gasp/core/output_file.h"
#include "gasp/core/pose.h"
#include "gasp/core/pose_perturbation.h"
#include "gasp/pipeline/depth_view.h"
#include "gasp/rawlog/rgbd_frame.h"

namespace gasp {

/// One (pose, sensory frame) pair per keyframe: the robot's pose T_world_camera[i]
/// T_robot_camera^-1 (T_robot_camera = the frame's own, MRPT's sensorPose), as a
/// CPose3DPDFGaussian, and a sensory frame holding the scan (observationFromFrame(); a LiDAR's
/// sweep as a CObservationRotatingScan, or a CObservationPointCloud when its returns carry their
/// own rays: toRotatingScan(), toPointCloud()). Its
/// covariance is covariance_world_camera[i] (the left perturbation [t r] of T_world_camera[i],
/// which is also the robot pose's: pose_graph_marginals.h) in [x y z yaw pitch roll]
/// (poseWithCovariance()), or zero when covariance_world_camera is empty. `with_points`: each
/// depth image's 3D points are stored in its observation too (in the camera's frame, as MRPT
/// unprojects them), which MRPT 2.5's points maps need to insert it -- about 3.7 MB more for a
/// 640x480 keyframe; a sweep is stored as a CObservation3DRangeScan of its points alone
/// (toPointsScan(): in the LiDAR's frame; MRPT 2.5's points maps insert it at the robot's pose, and
/// GASP reads it as a sweep, finding its layout again). Throws gasp::Error when the sizes differ, a
/// covariance is not finite and symmetric or a frame cannot be converted.
mrpt::maps::CSimpleMap keyframeSimpleMap(const std::vector<RgbdFrame>& keyframes,
                                         const std::vector<Isometry3>& T_world_camera,
                                         const std::vector<Matrix6>& covariance_world_camera = {},
                                         bool with_points = false);

/// The keyframe as GASP registered it, for the map: `frame` with the depth of `view`, the
/// keyframe's segmented view (DepthOdometry::keyframeView()). With rolling_shutter_readout_s the
/// odometry deskews a frame before segmenting it, and its pose is the deskewed depth's: the
/// recorded depth at that pose smears a moving camera's map by the motion during the readout.
/// The view's depth lies on the pinhole grid (lens distortion resampled away, makeDepthView()),
/// so the frame takes the view's intrinsics too; its raw depth is requantised at the frame's own
/// units (none when it had none), and its colour image is dropped: it no longer lies on the
/// depth's pixels. Timestamp, sensor label and mounting stay. Throws gasp::Error when the
/// view's depth is not CV_32FC1 of its intrinsics' size.
RgbdFrame withViewDepth(RgbdFrame frame, const DepthView& view);

/// Writes the map with MRPT's serialization, gzip-compressed as MRPT's own .simplemap files
/// (CSimpleMap::loadFromFile reads it), whole or not at all (gasp/core/output_file.h). Throws
/// gasp::Error naming the file when it cannot be written.
void saveSimpleMap(const mrpt::maps::CSimpleMap& map, const std::string& path);
/// The same into an output opened before the work; commits it.
void saveSimpleMap(const mrpt::maps::CSimpleMap& map, OutputFile& file);

}  // namespace gasp
