// CSuperpixelMap::computeObservationLikelihood: the observation's patches associated with the
// map's views of its kind (GASP's pose-invariant descriptors), each scored by its point-to-plane
// distance to its partner once the observation is placed at the given pose. A depth scan meets
// the map's depth views; a LiDAR sweep its sweeps, with the LiDAR's association settings
// (lidarAssociationParams()) and centroid distance (max_distance_m x lidarCentroidScale()).
//
// Only that last step depends on the pose. A particle filter asks for the same observation at
// every particle's pose, so the segmentation and the associations are kept for the last
// observation (LikelihoodCache) and each further pose costs a loop over the associations.
#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/core/exceptions.h>
#include <mrpt/maps/CPointsMap.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/obs/CObservationPointCloud.h>
#include <mrpt/obs/CObservationRotatingScan.h>
#include <mrpt/obs/CObservationVelodyneScan.h>

#include <algorithm>
#include <array>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "gasp/association/patch_geometry.h"
#include "gasp/association/view_association.h"
#include "gasp/core/error.h"
#include "gasp/mrpt/CSuperpixelMap.h"
#include "gasp/params/params_io.h"
#include "gasp/pipeline/range_view.h"
#include "gasp/rawlog/observation_conversion.h"
#include "gasp/rawlog/range_scan.h"

namespace gasp {

namespace {

/// Cost of an observation patch without a consistent partner: 3 sigma.
constexpr double kOutlierCost = 9.0;

std::size_t bytesHash(std::size_t seed, const void* data, std::size_t size) {
  return seed * 1099511628211ULL ^ std::hash<std::string_view>()(std::string_view(static_cast<const char*>(data), size));
}

/// A hash of a range image's raw values (contiguous storage), with its size.
std::size_t rangeImageHash(const mrpt::math::CMatrix_u16& range) {
  const std::size_t h = (static_cast<std::size_t>(range.rows()) << 20) ^ static_cast<std::size_t>(range.cols());
  return bytesHash(h, range.data(), static_cast<std::size_t>(range.size()) * sizeof(std::uint16_t));
}

/// A hash of a sweep's raw data as stored (isSweepObservation()): the range image of a rotating
/// scan, the packets of a Velodyne scan, the points of a point cloud or of a 3D scan of points.
std::size_t sweepHash(const mrpt::obs::CObservation& obs) {
  if (const auto* r = dynamic_cast<const mrpt::obs::CObservationRotatingScan*>(&obs)) {
    const std::array<double, 5> layout = {r->rangeResolution, r->startAzimuth, r->azimuthSpan, r->minRange, r->maxRange};
    return bytesHash(bytesHash(rangeImageHash(r->rangeImage), r->lidarModel.data(), r->lidarModel.size()), layout.data(),
                     sizeof layout);
  }
  if (const auto* v = dynamic_cast<const mrpt::obs::CObservationVelodyneScan*>(&obs))
    return bytesHash(v->scan_packets.size(), v->scan_packets.data(),
                     v->scan_packets.size() * sizeof(mrpt::obs::CObservationVelodyneScan::TVelodyneRawPacket));
  std::size_t h = 0;
  if (const auto* c = dynamic_cast<const mrpt::obs::CObservationPointCloud*>(&obs); c && c->pointcloud)
    for (const auto* xs : {&c->pointcloud->getPointsBufferRef_x(), &c->pointcloud->getPointsBufferRef_y(),
                           &c->pointcloud->getPointsBufferRef_z()})
      h = bytesHash(h ^ xs->size(), xs->data(), xs->size() * sizeof(float));
  if (const auto* s = dynamic_cast<const mrpt::obs::CObservation3DRangeScan*>(&obs))
    for (const auto* xs : {&s->points3D_x, &s->points3D_y, &s->points3D_z})
      h = bytesHash(h ^ xs->size(), xs->data(), xs->size() * sizeof(float));
  return h;
}

/// A write-only CConfigFileBase that appends every key to a string: the options' text without
/// the cost of an ini document (the options are compared on every call).
class OptionsText : public mrpt::config::CConfigFileBase {
 public:
  std::string text;
  void writeString(const std::string& section, const std::string& name, const std::string& str) override {
    // MRPT 2.5.8's write() without padding calls this twice with the same key and value (its
    // padded writeString() lacks a return after the plain call): the repeat is left out.
    std::string line = section + '\x1f' + name + '\x1f' + str + '\n';
    if (text.size() >= line.size() && text.compare(text.size() - line.size(), line.size(), line) == 0 &&
        (text.size() == line.size() || text[text.size() - line.size() - 1] == '\n'))
      return;
    text += line;
  }
  std::string readString(const std::string&, const std::string&, const std::string& default_str,
                         bool fail_if_not_found) const override {
    ASSERT_(!fail_if_not_found);
    return default_str;
  }
  void getAllSections(std::vector<std::string>&) const override {}
  void getAllKeys(const std::string&, std::vector<std::string>&) const override {}
  void clear() override { text.clear(); }
};

/// The options the cached part depends on, as text (segmentation and association keys).
std::string optionsText(const SuperpixelParams& superpixels, const LidarParams& lidar, const PairParams& matching) {
  OptionsText sink;
  writeSuperpixelParams(superpixels, sink, "s");
  writeLidarParams(lidar, sink, "l");
  writePairParams(matching, sink, "m");
  return std::move(sink.text);
}

}  // namespace

/// What the likelihood of one observation needs that does not depend on the pose.
struct CSuperpixelMap::LikelihoodCache::Entry {
  // The key: the observation as stored (its class, raw range image or sweep data, units, camera,
  // sensor pose, time, label) and the map's content and options. Nothing of it needs the
  // observation converted.
  std::string class_name;
  std::size_t range_hash = 0;
  float range_units = 0.0f;
  bool range_is_depth = true;
  mrpt::img::TCamera camera;
  std::array<double, 16> sensor_pose{};  ///< its homogeneous matrix, compared exactly
  mrpt::Clock::time_point timestamp;
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
  Isometry3 T_robot_camera = Isometry3::Identity();  ///< the sensor's pose on the robot
  double max_distance_scale = 1.0;  ///< a sweep's: lidarCentroidScale()
  /// False for a point cloud that is not one LiDAR's sweep (another sensor's): no information.
  bool usable = true;
  std::size_t seen_patches = 0;
  std::vector<Pair> pairs;

  bool sameKey(const Entry& o) const {
    return class_name == o.class_name && range_hash == o.range_hash && range_units == o.range_units && range_is_depth == o.range_is_depth &&
           camera == o.camera && sensor_pose == o.sensor_pose && timestamp == o.timestamp &&
           sensor_label == o.sensor_label && map_version == o.map_version && options == o.options;
  }
};

bool CSuperpixelMap::holdsViewsFor(const mrpt::obs::CObservation& obs) const {
  const bool sweep = isSweepObservation(obs);  // a 3D scan of points alone is a sweep
  const bool depth = !sweep && dynamic_cast<const mrpt::obs::CObservation3DRangeScan*>(&obs) != nullptr;
  if (!depth && !sweep) return false;
  for (const auto& view : views_)
    if ((view.view.returns == nullptr) == depth) return true;
  return false;
}

bool CSuperpixelMap::internal_canComputeObservationLikelihood(const mrpt::obs::CObservation& obs) const {
  return holdsViewsFor(obs);
}

std::shared_ptr<const CSuperpixelMap::LikelihoodCache::Entry> CSuperpixelMap::likelihoodEntry(
    const mrpt::obs::CObservation& obs) const {
  const auto* scan = dynamic_cast<const mrpt::obs::CObservation3DRangeScan*>(&obs);
  if (!scan || isSweepObservation(obs)) return sweepLikelihoodEntry(obs);
  // A scan whose range image is not in memory yet (stored externally) is converted first, which
  // loads and checks it; any other scan is converted only when the cache misses.
  std::optional<RgbdFrame> frame;
  const auto convert = [&] {
    try {
      frame = frameFromObservation(*scan, "CObservation3DRangeScan '" + scan->sensorLabel + "'", ColourImage::Skip);
    } catch (const Error& e) {
      THROW_EXCEPTION_FMT("gasp::CSuperpixelMap: %s", e.what());
    }
  };
  // MRPT's load() writes the image into the const scan (size first, then the values): calls for
  // an externally stored scan take turns, so none hashes an image while another loads it.
  std::unique_lock<std::mutex> load_lock(likelihood_cache_.load_mutex, std::defer_lock);
  if (scan->rangeImage_isExternallyStored() || scan->intensityImage.isExternallyStored()) load_lock.lock();
  if (!scan->hasRangeImage || scan->rangeImage.size() == 0) convert();
  auto entry = keyOf(*scan, rangeImageHash(scan->rangeImage));
  entry->range_units = scan->rangeUnits;
  entry->range_is_depth = scan->range_is_depth;
  entry->camera = scan->cameraParams;
  if (auto hit = cached(*entry)) return hit;

  if (!frame) convert();
  return associated(*frame, std::move(entry));
}

std::shared_ptr<CSuperpixelMap::LikelihoodCache::Entry> CSuperpixelMap::keyOf(const mrpt::obs::CObservation& obs,
                                                                              std::size_t data_hash) const {
  auto entry = std::make_shared<LikelihoodCache::Entry>();
  entry->class_name = obs.GetRuntimeClass()->className;
  entry->range_hash = data_hash;
  mrpt::poses::CPose3D sensor_pose;
  obs.getSensorPose(sensor_pose);
  const auto m = sensor_pose.getHomogeneousMatrixVal<mrpt::math::CMatrixDouble44>();
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) entry->sensor_pose[static_cast<std::size_t>(4 * r + c)] = m(r, c);
  entry->timestamp = obs.timestamp;
  entry->sensor_label = obs.sensorLabel;
  entry->map_version = content_version_;
  entry->options = optionsText(creationOptions.superpixels, creationOptions.lidar, likelihoodOptions.matching);
  return entry;
}

std::shared_ptr<const CSuperpixelMap::LikelihoodCache::Entry> CSuperpixelMap::cached(
    const LikelihoodCache::Entry& key) const {
  std::lock_guard<std::mutex> lock(likelihood_cache_.mutex);
  if (!likelihood_cache_.entry || !likelihood_cache_.entry->sameKey(key)) return nullptr;
  ++likelihood_cache_.hits;
  return likelihood_cache_.entry;
}

std::shared_ptr<const CSuperpixelMap::LikelihoodCache::Entry> CSuperpixelMap::sweepLikelihoodEntry(
    const mrpt::obs::CObservation& obs) const {
  // A point cloud kept in an external file is loaded first (MRPT's load() fills the const
  // observation in place), one call at a time, as the depth scans' images.
  const auto* cloud = dynamic_cast<const mrpt::obs::CObservationPointCloud*>(&obs);
  const auto* points = dynamic_cast<const mrpt::obs::CObservation3DRangeScan*>(&obs);  // of points alone
  std::unique_lock<std::mutex> load_lock(likelihood_cache_.load_mutex, std::defer_lock);
  if (cloud && cloud->isExternallyStored()) {
    load_lock.lock();
    cloud->load();
  }
  if (points && points->points3D_isExternallyStored()) {
    load_lock.lock();
    points->load();
  }
  auto entry = keyOf(obs, sweepHash(obs));
  if (auto hit = cached(*entry)) return hit;
  RgbdFrame frame;
  try {
    frame = sweepFrameFromObservation(obs, std::string(obs.GetRuntimeClass()->className) + " '" + obs.sensorLabel + "'");
    entry->max_distance_scale = lidarCentroidScale(creationOptions.lidar);
  } catch (const Error& e) {
    if (!isPointsObservation(obs)) THROW_EXCEPTION_FMT("gasp::CSuperpixelMap: %s", e.what());
    entry->usable = false;  // another sensor's points, not a sweep
    return stored(std::move(entry));
  }
  return associated(frame, std::move(entry));
}

std::shared_ptr<const CSuperpixelMap::LikelihoodCache::Entry> CSuperpixelMap::associated(
    const RgbdFrame& frame, std::shared_ptr<LikelihoodCache::Entry> entry) const {
  entry->T_robot_camera = frame.T_robot_camera;
  // Segmented in the robot frame (T_map_robot = identity): T_map_camera is then T_robot_camera.
  SuperpixelMapView seen;
  try {
    seen = makeMapView(frame, Isometry3::Identity(), creationOptions.superpixels, creationOptions.lidar);
  } catch (const Error& e) {
    THROW_EXCEPTION_FMT("gasp::CSuperpixelMap: %s", e.what());
  }
  const bool sweep = frame.isSweep();
  AssociationParams association = likelihoodOptions.matching.associate;
  try {
    if (sweep) association = lidarAssociationParams(association, creationOptions.lidar);
  } catch (const Error& e) {
    THROW_EXCEPTION_FMT("gasp::CSuperpixelMap: %s", e.what());
  }
  const auto& seen_patches = seen.view.segmentation.patches;
  entry->seen_patches = seen_patches.size();
  if (!seen_patches.empty()) {
    const auto geom_seen = toPatchGeometry(seen_patches);
    for (const auto& view : views_) {
      if ((view.view.returns != nullptr) != sweep) continue;  // the map's views of the observation's kind
      const AssociationResult r = associateViews(geom_seen, toPatchGeometry(view.view.segmentation.patches), association);
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
  return stored(std::move(entry));
}

std::shared_ptr<const CSuperpixelMap::LikelihoodCache::Entry> CSuperpixelMap::stored(
    std::shared_ptr<LikelihoodCache::Entry> entry) const {
  std::lock_guard<std::mutex> lock(likelihood_cache_.mutex);
  ++likelihood_cache_.misses;
  likelihood_cache_.entry = entry;
  return entry;
}

double CSuperpixelMap::internal_computeObservationLikelihood(const mrpt::obs::CObservation& obs,
                                                             const mrpt::poses::CPose3D& takenFrom) const {
  if (!holdsViewsFor(obs)) return 0.0;  // no information (see the header)
  const auto entry = likelihoodEntry(obs);
  if (!entry->usable) return 0.0;
  if (entry->seen_patches == 0) return -0.5 * kOutlierCost;
  const Isometry3 T_map_camera = fromCPose3D(takenFrom) * entry->T_robot_camera;
  const double sigma = likelihoodOptions.sigma_m, max_d = likelihoodOptions.max_distance_m * entry->max_distance_scale;
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
