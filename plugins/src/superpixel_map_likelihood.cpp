// CSuperpixelMap::computeObservationLikelihood: the observation's patches associated with the
// map's (GASP's pose-invariant descriptors), each scored by its point-to-plane distance to its
// partner once the observation is placed at the given pose.
//
// Only that last step depends on the pose. A particle filter asks for the same observation at
// every particle's pose, so the segmentation and the associations are kept for the last
// observation (LikelihoodCache) and each further pose costs a loop over the associations.
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/core/exceptions.h>
#include <mrpt/obs/CObservation3DRangeScan.h>

#include <algorithm>
#include <functional>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

#include "gasp/association/patch_geometry.h"
#include "gasp/association/view_association.h"
#include "gasp/core/error.h"
#include "gasp/mrpt/CSuperpixelMap.h"
#include "gasp/mrpt/params_io.h"
#include "gasp/rawlog/observation_conversion.h"

namespace gasp {

namespace {

/// Cost of an observation patch without a consistent partner: 3 sigma.
constexpr double kOutlierCost = 9.0;

/// A hash of an image's pixels (rows of any step).
std::size_t pixelHash(const cv::Mat& image) {
  std::size_t h = std::hash<int>()(image.type()) ^ (static_cast<std::size_t>(image.rows) << 20) ^
                  static_cast<std::size_t>(image.cols);
  const std::size_t row_bytes = static_cast<std::size_t>(image.cols) * image.elemSize();
  for (int r = 0; r < image.rows; ++r)
    h = h * 1099511628211ULL ^ std::hash<std::string_view>()(std::string_view(image.ptr<char>(r), row_bytes));
  return h;
}

/// The options the cached part depends on, as ini text (segmentation and association keys).
std::string optionsText(const SuperpixelParams& superpixels, const PairParams& matching) {
  mrpt::config::CConfigFileMemory memory;
  writeSuperpixelParams(superpixels, memory, "s");
  writePairParams(matching, memory, "m");
  std::string text;
  memory.getContent(text);
  return text;
}

}  // namespace

/// What the likelihood of one observation needs that does not depend on the pose.
struct CSuperpixelMap::LikelihoodCache::Entry {
  // The key: the observation (converted frame) and the map's content and options.
  std::size_t depth_hash = 0;
  CameraIntrinsics intrinsics;
  Isometry3 T_robot_camera = Isometry3::Identity();
  double timestamp = 0.0;
  std::string sensor_label;
  std::uint64_t map_version = 0;
  std::string options;

  /// An observation patch and a map patch the association paired.
  struct Pair {
    int seen = 0;                                          ///< patch of the observation
    Eigen::Vector3d centroid_camera = Eigen::Vector3d::Zero();  ///< its centroid, depth camera frame
    Eigen::Vector3d map_centroid = Eigen::Vector3d::Zero();     ///< partner's centroid, map frame
    Eigen::Vector3d map_normal = Eigen::Vector3d::UnitZ();      ///< partner's normal, map frame
  };
  std::size_t seen_patches = 0;
  std::vector<Pair> pairs;

  bool sameKey(const Entry& o) const {
    return depth_hash == o.depth_hash && intrinsics == o.intrinsics && T_robot_camera.isApprox(o.T_robot_camera, 0.0) &&
           timestamp == o.timestamp && sensor_label == o.sensor_label && map_version == o.map_version &&
           options == o.options;
  }
};

bool CSuperpixelMap::internal_canComputeObservationLikelihood(const mrpt::obs::CObservation& obs) const {
  return !isEmpty() && dynamic_cast<const mrpt::obs::CObservation3DRangeScan*>(&obs) != nullptr;
}

std::shared_ptr<const CSuperpixelMap::LikelihoodCache::Entry> CSuperpixelMap::likelihoodEntry(
    const mrpt::obs::CObservation3DRangeScan& scan) const {
  RgbdFrame frame;
  try {
    frame = frameFromObservation(scan, "CObservation3DRangeScan '" + scan.sensorLabel + "'");
  } catch (const Error& e) {
    THROW_EXCEPTION_FMT("gasp::CSuperpixelMap: %s", e.what());
  }
  auto entry = std::make_shared<LikelihoodCache::Entry>();
  entry->depth_hash = pixelHash(frame.depth_m);
  entry->intrinsics = frame.depth_intrinsics;
  entry->T_robot_camera = frame.T_robot_camera;
  entry->timestamp = frame.timestamp;
  entry->sensor_label = frame.sensor_label;
  entry->map_version = content_version_;
  entry->options = optionsText(creationOptions.superpixels, likelihoodOptions.matching);
  {
    std::lock_guard<std::mutex> lock(likelihood_cache_.mutex);
    if (likelihood_cache_.entry && likelihood_cache_.entry->sameKey(*entry)) {
      ++likelihood_cache_.hits;
      return likelihood_cache_.entry;
    }
  }

  // Segmented in the robot frame (T_map_robot = identity): T_map_camera is then T_robot_camera.
  SuperpixelMapView seen;
  try {
    frame.rgb.release();  // colours are not needed here
    seen = makeMapView(frame, Isometry3::Identity(), creationOptions.superpixels);
  } catch (const Error& e) {
    THROW_EXCEPTION_FMT("gasp::CSuperpixelMap: %s", e.what());
  }
  const auto& seen_patches = seen.view.segmentation.patches;
  entry->seen_patches = seen_patches.size();
  if (!seen_patches.empty()) {
    const auto geom_seen = toPatchGeometry(seen_patches);
    for (const auto& view : views_) {
      const AssociationResult r =
          associateViews(geom_seen, toPatchGeometry(view.view.segmentation.patches), likelihoodOptions.matching.association);
      for (const PatchAssociation& s : r.associations) {
        const SurfacePatch& m = view.view.segmentation.patches[static_cast<std::size_t>(s.b)];
        LikelihoodCache::Entry::Pair p;
        p.seen = s.a;
        p.centroid_camera = seen_patches[static_cast<std::size_t>(s.a)].centroid;
        p.map_centroid = view.T_map_camera * m.centroid;
        p.map_normal = view.T_map_camera.linear() * m.normal;
        entry->pairs.push_back(p);
      }
    }
  }
  std::lock_guard<std::mutex> lock(likelihood_cache_.mutex);
  ++likelihood_cache_.misses;
  likelihood_cache_.entry = entry;
  return entry;
}

double CSuperpixelMap::internal_computeObservationLikelihood(const mrpt::obs::CObservation& obs,
                                                             const mrpt::poses::CPose3D& takenFrom) const {
  const auto* scan = dynamic_cast<const mrpt::obs::CObservation3DRangeScan*>(&obs);
  if (!scan || isEmpty()) return 0.0;  // no information (see the header)
  const auto entry = likelihoodEntry(*scan);
  if (entry->seen_patches == 0) return -0.5 * kOutlierCost;
  const Isometry3 T_map_camera = fromCPose3D(takenFrom) * entry->T_robot_camera;
  const double sigma = likelihoodOptions.sigma_m, max_d = likelihoodOptions.max_distance_m;
  std::vector<double> cost(entry->seen_patches, kOutlierCost);
  for (const auto& pair : entry->pairs) {
    const Eigen::Vector3d p = T_map_camera * pair.centroid_camera;
    if ((p - pair.map_centroid).norm() > max_d) continue;
    const double d = std::abs(pair.map_normal.dot(p - pair.map_centroid)) / sigma;
    double& c = cost[static_cast<std::size_t>(pair.seen)];
    c = std::min(c, std::min(d * d, kOutlierCost));
  }
  double sum = 0;
  for (double c : cost) sum += c;
  return -0.5 * sum / static_cast<double>(cost.size());
}

}  // namespace gasp
