#include "gasp/mrpt/superpixel_map_view.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "gasp/core/error.h"
#include "gasp/core/undistortion.h"
#include "gasp/pipeline/range_view.h"

namespace gasp {

namespace {

std::string sizeText(int w, int h) { return std::to_string(w) + "x" + std::to_string(h); }

/// Mean colour of each patch's pixels (every 2nd pixel each way) seen by the intensity camera.
std::vector<Rgb8> patchColours(const RgbdFrame& frame, const DepthView& view) {
  const SuperpixelSegmentation& seg = view.segmentation;
  CameraIntrinsics k_rgb = frame.rgb_intrinsics;
  k_rgb.validate();
  if (frame.rgb.cols != k_rgb.width || frame.rgb.rows != k_rgb.height) {
    throw Error("inconsistent intrinsics: the intensity image is " + sizeText(frame.rgb.cols, frame.rgb.rows) +
                " but the intensity camera (cameraParamsIntensity) is " + sizeText(k_rgb.width, k_rgb.height));
  }
  if (frame.rgb.type() != CV_8UC3) throw Error("intensity image: expected 8-bit BGR");
  // The depth view is pinhole (makeDepthView resampled it); so is the colour image looked up here.
  cv::Mat image = frame.rgb;
  if (hasLensDistortion(k_rgb)) {
    const auto undistortion = sharedUndistortion(k_rgb);
    image = undistortion->applyToImage(image);
    k_rgb = undistortion->pinhole();
  }
  const std::size_t n = seg.patches.size();
  std::vector<Eigen::Vector3d> sum(n, Eigen::Vector3d::Zero());
  std::vector<int> count(n, 0);
  const Isometry3 T_rgb_depth = frame.T_depth_rgb.inverse();
  const CameraIntrinsics& k = view.projection.pinhole();  // the view's (undistorted) depth, as its labels
  for (int v = 0; v < seg.labels.rows; v += 2) {
    const int* label = seg.labels.ptr<int>(v);
    const float* depth = view.depth_m.ptr<float>(v);
    for (int u = 0; u < seg.labels.cols; u += 2) {
      if (label[u] < 0) continue;
      const Eigen::Vector3d p_rgb = T_rgb_depth * k.unproject(u, v, depth[u]);
      double ur = 0, vr = 0;
      if (!k_rgb.project(p_rgb, ur, vr)) continue;
      const int iu = static_cast<int>(std::lround(ur)), iv = static_cast<int>(std::lround(vr));
      if (iu < 0 || iv < 0 || iu >= image.cols || iv >= image.rows) continue;
      const cv::Vec3b bgr = image.at<cv::Vec3b>(iv, iu);
      sum[static_cast<std::size_t>(label[u])] += Eigen::Vector3d(bgr[2], bgr[1], bgr[0]);
      ++count[static_cast<std::size_t>(label[u])];
    }
  }
  std::vector<Rgb8> rgb(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (count[i] == 0) {
      rgb[i] = normalColour(seg.patches[i].normal);
      continue;
    }
    const Eigen::Vector3d m = sum[i] / count[i];
    for (int c = 0; c < 3; ++c) rgb[i][static_cast<std::size_t>(c)] = static_cast<std::uint8_t>(std::lround(m[c]));
  }
  return rgb;
}

bool finite(const Eigen::Vector3d& v) { return v.allFinite(); }

}  // namespace

Rgb8 normalColour(const Eigen::Vector3d& normal) {
  Rgb8 c{};
  for (int i = 0; i < 3; ++i) {
    const double x = std::isfinite(normal[i]) ? normal[i] : 0.0;
    c[static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(std::lround(127.5 * (1.0 + std::clamp(x, -1.0, 1.0))));
  }
  return c;
}

SuperpixelMapView makeMapView(const RgbdFrame& frame, const Isometry3& T_map_robot, const SuperpixelParams& params,
                              const LidarParams& lidar) {
  SuperpixelMapView v;
  if (frame.isSweep()) {
    v.view = makeRangeView(*frame.sweep, lidarSuperpixelParams(lidar), returnsRefineParams(lidar));
  } else {
    frame.depth_intrinsics.validate();
    v.view = makeDepthView(frame.depth_m, frame.depth_intrinsics, params);
  }
  v.T_map_camera = T_map_robot * frame.T_robot_camera;
  if (frame.hasRgb() && !frame.isSweep()) v.patch_rgb = patchColours(frame, v.view);
  v.timestamp = frame.timestamp;
  v.sensor_label = frame.sensor_label;
  return v;
}

void appendMapPatches(const SuperpixelMapView& view, int view_index, std::vector<MapPatch>& out) {
  const auto& patches = view.view.segmentation.patches;
  const Eigen::Matrix3d R = view.T_map_camera.linear();
  for (std::size_t i = 0; i < patches.size(); ++i) {
    const SurfacePatch& s = patches[i];
    MapPatch m;
    m.centroid = view.T_map_camera * s.centroid;
    m.normal = (R * s.normal).normalized();
    m.area_m2 = s.area_m2;
    m.radius_m = s.radius();
    m.rgb = view.patch_rgb.empty() ? normalColour(s.normal) : view.patch_rgb[i];
    m.view = view_index;
    m.patch = static_cast<int>(i);
    out.push_back(m);
  }
}

void checkConsistency(const SuperpixelMapView& v) {
  const ViewProjection& k = v.view.projection;
  if (k.isPinhole())
    k.pinhole().validate();
  else
    k.grid().validate();
  const cv::Mat& depth = v.view.depth_m;
  const SuperpixelSegmentation& seg = v.view.segmentation;
  if (depth.type() != CV_32FC1 || depth.cols != k.width() || depth.rows != k.height())
    throw Error("depth image is not " + sizeText(k.width(), k.height()) + " CV_32FC1");
  if (seg.labels.type() != CV_32SC1 || seg.labels.size() != depth.size())
    throw Error("label image does not match the depth image");
  const int n = static_cast<int>(seg.patches.size());
  for (int r = 0; r < seg.labels.rows; ++r) {
    const int* l = seg.labels.ptr<int>(r);
    for (int c = 0; c < seg.labels.cols; ++c)
      if (l[c] < -1 || l[c] >= n) throw Error("label " + std::to_string(l[c]) + " out of range (patches: " + std::to_string(n) + ")");
  }
  for (int i = 0; i < n; ++i) {
    const SurfacePatch& s = seg.patches[static_cast<std::size_t>(i)];
    if (s.id != i) throw Error("patch " + std::to_string(i) + " has id " + std::to_string(s.id));
    if (!finite(s.centroid) || !finite(s.normal) || std::abs(s.normal.norm() - 1.0) > 1e-3 || !(s.area_m2 >= 0) ||
        !std::isfinite(s.area_m2) || !s.covariance.allFinite() || !std::isfinite(s.planarity))
      throw Error("patch " + std::to_string(i) + " has non-finite values or a normal that is not unit");
  }
  if (seg.adjacency.size() != seg.patches.size()) throw Error("adjacency list size differs from the patch count");
  for (const auto& list : seg.adjacency)
    for (int j : list)
      if (j < 0 || j >= n) throw Error("adjacency refers to patch " + std::to_string(j) + " of " + std::to_string(n));
  if (!v.patch_rgb.empty() && v.patch_rgb.size() != seg.patches.size())
    throw Error("colour count differs from the patch count");
  if (!v.T_map_camera.matrix().allFinite()) throw Error("camera pose is not finite");
}

}  // namespace gasp
