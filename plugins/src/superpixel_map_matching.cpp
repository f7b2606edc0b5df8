// CSuperpixelMap::compute3DMatchingRatio from GASP's patch associations (pose-invariant
// descriptors) checked against the given pose; the likelihood is in superpixel_map_likelihood.cpp.
#include <mrpt/core/exceptions.h>
#include <mrpt/maps/CMultiMetricMap.h>

#include <algorithm>
#include <set>

#include "gasp/association/patch_geometry.h"
#include "gasp/association/view_association.h"
#include "gasp/core/error.h"
#include "gasp/mrpt/CSuperpixelMap.h"
#include "gasp/rawlog/observation_conversion.h"

namespace gasp {

namespace {

std::vector<PatchGeometry> geometry(const SuperpixelMapView& v) {
  return toPatchGeometry(v.view.segmentation.patches);
}

const SurfacePatch& patchOf(const SuperpixelMapView& v, int i) {
  return v.view.segmentation.patches[static_cast<std::size_t>(i)];
}

}  // namespace

const CSuperpixelMap* CSuperpixelMap::findIn(const mrpt::maps::CMetricMap* m, std::string* why) {
  auto say = [&](const std::string& text) {
    if (why) *why = text;
    return nullptr;
  };
  if (!m) return say("the map is null");
  if (const auto* s = dynamic_cast<const CSuperpixelMap*>(m)) return s;
  const auto* multi = dynamic_cast<const mrpt::maps::CMultiMetricMap*>(m);
  if (!multi)
    return say(std::string("it is a ") + m->GetRuntimeClass()->className +
               ", neither a gasp::CSuperpixelMap nor a CMultiMetricMap holding one");
  const CSuperpixelMap* found = nullptr;
  std::size_t count = 0;
  for (const auto& sub : multi->maps)
    if (const auto* s = dynamic_cast<const CSuperpixelMap*>(sub.get())) found = s, ++count;
  if (count == 1) return found;
  return say("it is a CMultiMetricMap holding " + std::to_string(count) +
             " gasp::CSuperpixelMap (one is needed)");
}

float CSuperpixelMap::compute3DMatchingRatio(const mrpt::maps::CMetricMap* otherMap,
                                             const mrpt::poses::CPose3D& otherMapPose,
                                             const mrpt::maps::TMatchingRatioParams& params) const {
  const CSuperpixelMap* other = findIn(otherMap);
  if (!other || isEmpty() || other->isEmpty()) return 0.0f;
  const Isometry3 T_this_other = fromCPose3D(otherMapPose);
  const double max_d = params.maxDistForCorr;
  std::set<std::pair<int, int>> matched_this, matched_other;
  for (std::size_t i = 0; i < views_.size(); ++i) {
    const auto geom_i = geometry(views_[i]);
    for (std::size_t j = 0; j < other->views_.size(); ++j) {
      const auto& vj = other->views_[j];
      const AssociationResult r = associateViews(geom_i, geometry(vj), likelihoodOptions.matching.associate);
      const Isometry3 T_this_cj = T_this_other * vj.T_map_camera;
      for (const PatchAssociation& s : r.associations) {
        const Eigen::Vector3d p = views_[i].T_map_camera * patchOf(views_[i], s.a).centroid;
        const Eigen::Vector3d q = T_this_cj * patchOf(vj, s.b).centroid;
        if ((p - q).norm() > max_d) continue;
        matched_this.emplace(static_cast<int>(i), s.a);
        matched_other.emplace(static_cast<int>(j), s.b);
      }
    }
  }
  const std::size_t smaller = std::min(patchCount(), other->patchCount());
  const std::size_t matched = std::min(matched_this.size(), matched_other.size());
  return smaller ? static_cast<float>(static_cast<double>(matched) / static_cast<double>(smaller)) : 0.0f;
}

}  // namespace gasp
