#pragma once
/// \file CSuperpixelMap.h A metric map of GASP surface patches (depth superpixels).
///
/// Each inserted mrpt::obs::CObservation3DRangeScan (RGB-D or range-only) is segmented into
/// patches (SuperpixelParams = the map's creation options) and kept as one view: its depth image
/// and depth intrinsics (cameraParams), its patches in the depth camera's frame, and
/// T_map_camera = robotPose * sensorPose (optical frame). Colours come from the intensity image
/// through cameraParamsIntensity and relativePoseIntensityWRTDepth. Views are kept whole so that
/// CGaspAligner and the likelihood can run GASP's association on them.
///
/// In a CMultiMetricMap ini section (docs/mrpt.md):
///   superpixelMap_count=1
///   [<section>_superpixelMap_00_creationOpts]    SuperpixelParams keys, e.g. target_patch_area_m2=0.004
///   [<section>_superpixelMap_00_likelihoodOpts]  matching keys and sigma_m, max_distance_m
///   [<section>_superpixelMap_00_renderOpts]      style=discs|points, point_step_px
#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/maps/CMetricMap.h>
#include <mrpt/obs/CObservation3DRangeScan.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "gasp/mrpt/superpixel_map_view.h"
#include "gasp/pipeline/pair_registration.h"

namespace gasp {

class CSuperpixelMap : public mrpt::maps::CMetricMap {
  DEFINE_SERIALIZABLE(CSuperpixelMap, gasp)

 public:
  /// Segmentation of inserted observations (ini section ..._creationOpts).
  struct TCreationOptions : public mrpt::config::CLoadableOptions {
    SuperpixelParams superpixels;  ///< depth images
    /// LiDAR sweeps (CObservationRotatingScan, CObservationVelodyneScan, CObservationPointCloud): lidarSuperpixelParams()
    /// and the returns' normals of these; the same section, the params file's lidar keys.
    LidarParams lidar;
    void loadFromConfigFile(const mrpt::config::CConfigFileBase& source, const std::string& section) override;
    void saveToConfigFile(mrpt::config::CConfigFileBase& target, const std::string& section) const override;
  };
  /// computeObservationLikelihood / compute3DMatchingRatio (ini section ..._likelihoodOpts).
  struct TLikelihoodOptions : public mrpt::config::CLoadableOptions {
    PairParams matching;   ///< association keys of params_io.h (segmentation comes from the map's)
    double sigma_m = 0.02;  ///< std. dev. of a patch's point-to-plane distance to its partner [m]
    /// Associated patches whose centroids are further apart than this (after placing the
    /// observation) count as outliers [m].
    double max_distance_m = 0.10;
    void loadFromConfigFile(const mrpt::config::CConfigFileBase& source, const std::string& section) override;
    void saveToConfigFile(mrpt::config::CConfigFileBase& target, const std::string& section) const override;
  };
  /// getVisualizationInto (ini section ..._renderOpts).
  struct TRenderOptions : public mrpt::config::CLoadableOptions {
    enum class Style { discs, points };
    Style style = Style::discs;  ///< oriented discs of the patches' area, or their pixels as points
    int point_step_px = 2;       ///< points style: every n-th pixel each way
    void loadFromConfigFile(const mrpt::config::CConfigFileBase& source, const std::string& section) override;
    void saveToConfigFile(mrpt::config::CConfigFileBase& target, const std::string& section) const override;
  };

  TCreationOptions creationOptions;
  TLikelihoodOptions likelihoodOptions;
  TRenderOptions renderOptions;

  CSuperpixelMap() = default;

  /// Inserts a frame (what insertObservation does after converting the scan). Throws
  /// std::exception (MRPT style) for bad images or inconsistent intrinsics.
  void insertFrame(const RgbdFrame& frame, const Isometry3& T_map_robot = Isometry3::Identity());

  const std::vector<SuperpixelMapView>& views() const { return views_; }
  std::size_t patchCount() const;
  /// All patches in the map frame.
  std::vector<MapPatch> patchesInMapFrame() const;

  bool isEmpty() const override { return views_.empty(); }
  std::string asString() const override;
  void getVisualizationInto(mrpt::opengl::CSetOfObjects& o) const override;
  /// Writes PREFIX_patches.ply (one vertex per patch: centroid, normal, colour, area),
  /// PREFIX_patches.txt (a table: view, patch, centroid, normal, area, pixels, planarity, colour)
  /// and PREFIX_3D.3Dscene (getVisualizationInto, for SceneViewer3D).
  void saveMetricMapRepresentationToFile(const std::string& prefix) const override;
  /// `m` itself when it is a CSuperpixelMap; the only CSuperpixelMap inside a CMultiMetricMap
  /// (what CMultiMetricMap passes on to its maps); else nullptr, with the reason in `why`.
  static const CSuperpixelMap* findIn(const mrpt::maps::CMetricMap* m, std::string* why = nullptr);

  /// Fraction of the patches (of the smaller map) whose GASP association partner lies within
  /// params.maxDistForCorr once `otherMap` (a CSuperpixelMap, or a CMultiMetricMap holding one:
  /// findIn) is placed at otherMapPose. 0 for other map types.
  float compute3DMatchingRatio(const mrpt::maps::CMetricMap* otherMap, const mrpt::poses::CPose3D& otherMapPose,
                               const mrpt::maps::TMatchingRatioParams& params) const override;

  /// The likelihood keeps the last observation's segmentation and associations and reuses them
  /// while it is asked for the same observation at other poses (a particle filter asks once per
  /// particle). A hit needs the same raw range image, range units, camera, sensor pose, timestamp
  /// and label, the same map content and the same segmentation and association options.
  struct LikelihoodCacheStats {
    std::size_t hits = 0;    ///< calls that reused the last observation's associations
    std::size_t misses = 0;  ///< calls that segmented and associated the observation
  };
  LikelihoodCacheStats likelihoodCacheStats() const;

  MAP_DEFINITION_START(CSuperpixelMap)
  TCreationOptions creationOpts;
  TLikelihoodOptions likelihoodOpts;
  TRenderOptions renderOpts;
  MAP_DEFINITION_END(CSuperpixelMap)

 private:
  void internal_clear() override {
    views_.clear();
    ++content_version_;
  }
  /// CObservation3DRangeScan, and a LiDAR's CObservationRotatingScan, CObservationVelodyneScan or
  /// CObservationPointCloud (creationOptions.lidar): inserted (true). Other observation types, and
  /// a point cloud that is not one LiDAR's sweep (another sensor's: no rings), give false, as
  /// every MRPT map does for what it cannot use (CMultiMetricMap offers each observation to every
  /// map). A scan without range image or with inconsistent intrinsics, or a sweep of a model whose
  /// elevations GASP does not know, throws.
  bool internal_insertObservation(const mrpt::obs::CObservation& obs,
                                  const std::optional<const mrpt::poses::CPose3D>& robotPose) override;
  /// log-likelihood of a CObservation3DRangeScan or a LiDAR sweep (isSweepObservation()) taken
  /// from `takenFrom`: its patches are associated with the map's views of its kind (GASP; a
  /// sweep's with lidarAssociationParams() of the matching keys); each contributes
  /// -0.5 min((d / sigma_m)^2, 9), d the point-to-plane distance to its partner, 9 (3 sigma) for
  /// patches without a consistent one (centroids further apart than max_distance_m, for a sweep
  /// times lidarCentroidScale()); the mean over the observation's patches is returned. 0 (no
  /// information) for other observation types, for a point cloud that is not one LiDAR's sweep
  /// and for a map without views of its kind, as MRPT's own maps answer for what they cannot use:
  /// CMetricMap::computeObservationsLikelihood and CMultiMetricMap add every map's answer for
  /// every observation without asking canComputeObservationLikelihood first. A scan that cannot
  /// be read throws.
  double internal_computeObservationLikelihood(const mrpt::obs::CObservation& obs,
                                               const mrpt::poses::CPose3D& takenFrom) const override;
  bool internal_canComputeObservationLikelihood(const mrpt::obs::CObservation& obs) const override;

  /// The last observation's pose-free likelihood data (superpixel_map_likelihood.cpp). Copies
  /// of the map start with an empty cache; it is not serialised. The mutex makes the const
  /// likelihood safe to call from several threads; `load_mutex` serialises the calls for a scan
  /// stored in external files (MRPT's load() fills the const observation in place).
  struct LikelihoodCache {
    struct Entry;
    std::shared_ptr<const Entry> entry;
    std::size_t hits = 0, misses = 0;
    std::mutex mutex;
    std::mutex load_mutex;
    LikelihoodCache() = default;
    LikelihoodCache(const LikelihoodCache&) {}
    LikelihoodCache& operator=(const LikelihoodCache&) {
      std::lock_guard<std::mutex> lock(mutex);
      entry.reset();
      return *this;
    }
  };
  /// The cache entry for a depth scan or a sweep (computed, or the last one when its key matches).
  std::shared_ptr<const LikelihoodCache::Entry> likelihoodEntry(const mrpt::obs::CObservation& obs) const;
  std::shared_ptr<const LikelihoodCache::Entry> sweepLikelihoodEntry(const mrpt::obs::CObservation& obs) const;
  /// A new entry with the key of `obs` (its raw data's hash given) and of the map.
  std::shared_ptr<LikelihoodCache::Entry> keyOf(const mrpt::obs::CObservation& obs, std::size_t data_hash) const;
  /// The cached entry when its key is `key`'s (counted as a hit), else null.
  std::shared_ptr<const LikelihoodCache::Entry> cached(const LikelihoodCache::Entry& key) const;
  /// `entry` completed with the frame's patches and their partners among the map's views of the
  /// frame's kind, and stored().
  std::shared_ptr<const LikelihoodCache::Entry> associated(const RgbdFrame& frame,
                                                           std::shared_ptr<LikelihoodCache::Entry> entry) const;
  /// `entry` made the cached one (counted as a miss).
  std::shared_ptr<const LikelihoodCache::Entry> stored(std::shared_ptr<LikelihoodCache::Entry> entry) const;
  /// A depth scan with a depth view in the map, or a sweep with a sweep view.
  bool holdsViewsFor(const mrpt::obs::CObservation& obs) const;

  std::vector<SuperpixelMapView> views_;
  std::uint64_t content_version_ = 0;  ///< changes with every change of views_ (the cache's key)
  mutable LikelihoodCache likelihood_cache_;
};

}  // namespace gasp
