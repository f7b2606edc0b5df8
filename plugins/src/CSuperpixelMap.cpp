#include "gasp/mrpt/CSuperpixelMap.h"

#include <mrpt/core/exceptions.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/obs/CObservationPointCloud.h>

#include <sstream>

#include "gasp/core/error.h"
#include "gasp/rawlog/observation_conversion.h"
#include "gasp/rawlog/range_scan.h"

IMPLEMENTS_SERIALIZABLE(CSuperpixelMap, mrpt::maps::CMetricMap, gasp)

namespace gasp {

void CSuperpixelMap::insertFrame(const RgbdFrame& frame, const Isometry3& T_map_robot) {
  try {
    views_.push_back(makeMapView(frame, T_map_robot, creationOptions.superpixels, creationOptions.lidar));
    ++content_version_;
  } catch (const Error& e) {
    THROW_EXCEPTION_FMT("gasp::CSuperpixelMap: cannot insert observation '%s': %s", frame.sensor_label.c_str(),
                        e.what());
  }
}

bool CSuperpixelMap::internal_insertObservation(const mrpt::obs::CObservation& obs,
                                                const std::optional<const mrpt::poses::CPose3D>& robotPose) {
  const bool sweep = isSweepObservation(obs);  // first: a 3D scan of points alone is a sweep
  const auto* scan = sweep ? nullptr : dynamic_cast<const mrpt::obs::CObservation3DRangeScan*>(&obs);
  if (!scan && !sweep) return false;
  RgbdFrame frame;
  try {
    frame = scan ? frameFromObservation(*scan, "CObservation3DRangeScan '" + scan->sensorLabel + "'")
                 : sweepFrameFromObservation(obs, std::string(obs.GetRuntimeClass()->className) + " '" + obs.sensorLabel + "'");
  } catch (const Error& e) {
    // Bare points that are not one LiDAR's sweep are another sensor's: not for this map.
    if (isPointsObservation(obs)) return false;
    THROW_EXCEPTION_FMT("gasp::CSuperpixelMap: %s", e.what());
  }
  insertFrame(frame, robotPose ? fromCPose3D(*robotPose) : Isometry3::Identity());
  return true;
}

CSuperpixelMap::LikelihoodCacheStats CSuperpixelMap::likelihoodCacheStats() const {
  std::lock_guard<std::mutex> lock(likelihood_cache_.mutex);
  return {likelihood_cache_.hits, likelihood_cache_.misses};
}

std::size_t CSuperpixelMap::patchCount() const {
  std::size_t n = 0;
  for (const auto& v : views_) n += v.view.segmentation.patches.size();
  return n;
}

std::vector<MapPatch> CSuperpixelMap::patchesInMapFrame() const {
  std::vector<MapPatch> out;
  out.reserve(patchCount());
  for (std::size_t i = 0; i < views_.size(); ++i) appendMapPatches(views_[i], static_cast<int>(i), out);
  return out;
}

std::string CSuperpixelMap::asString() const {
  std::ostringstream s;
  s << "gasp::CSuperpixelMap: " << views_.size() << " views, " << patchCount() << " surface patches";
  return s.str();
}

}  // namespace gasp
