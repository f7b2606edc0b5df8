// CSuperpixelMap's options and its map definition (CMultiMetricMap / TSetOfMetricMapInitializers).
#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/core/exceptions.h>

#include <memory>
#include <ostream>

#include "gasp/mrpt/CSuperpixelMap.h"
#include "gasp/params/params_io.h"

namespace gasp {

namespace {
// Keys of TMapGenericParams, which MRPT reads from the same ..._creationOpts section.
const std::set<std::string> kGenericKeys{"enableSaveAs3DObject", "enableObservationLikelihood",
                                         "enableObservationInsertion"};
}  // namespace

void CSuperpixelMap::TCreationOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& source,
                                                          const std::string& section) {
  SuperpixelParams s = superpixels;  // both read, or neither changed
  LidarParams l = lidar;
  std::set<std::string> others = kGenericKeys;
  for (const std::string& k : lidarKeys()) others.insert(k);
  readSuperpixelParams(source, section, s, others);
  others = kGenericKeys;
  for (const std::string& k : superpixelKeys()) others.insert(k);
  readLidarParams(source, section, l, others);
  superpixels = s;
  lidar = l;
}

void CSuperpixelMap::TCreationOptions::saveToConfigFile(mrpt::config::CConfigFileBase& target,
                                                        const std::string& section) const {
  writeSuperpixelParams(superpixels, target, section);
  writeLidarParams(lidar, target, section);
}

void CSuperpixelMap::TLikelihoodOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& source,
                                                            const std::string& section) {
  double sigma = sigma_m, max_distance = max_distance_m;
  readValue(source, section, "sigma_m", sigma);
  readValue(source, section, "max_distance_m", max_distance);
  if (!(sigma > 0)) THROW_EXCEPTION_FMT("[%s] sigma_m must be > 0, got %g", section.c_str(), sigma);
  if (!(max_distance > 0)) THROW_EXCEPTION_FMT("[%s] max_distance_m must be > 0, got %g", section.c_str(), max_distance);
  readPairParams(source, section, matching, {"sigma_m", "max_distance_m"});
  sigma_m = sigma;
  max_distance_m = max_distance;
}

void CSuperpixelMap::TLikelihoodOptions::saveToConfigFile(mrpt::config::CConfigFileBase& target,
                                                          const std::string& section) const {
  writePairParams(matching, target, section);
  writeValue(target, section, "sigma_m", sigma_m);
  writeValue(target, section, "max_distance_m", max_distance_m);
}

void CSuperpixelMap::TRenderOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& source,
                                                        const std::string& section) {
  checkKeys(source, section, {"style", "point_step_px"});
  const std::string s = source.read_string(section, "style", style == Style::discs ? "discs" : "points");
  Style new_style;
  if (s == "discs")
    new_style = Style::discs;
  else if (s == "points")
    new_style = Style::points;
  else
    THROW_EXCEPTION_FMT("[%s] style = '%s': expected discs or points", section.c_str(), s.c_str());
  int step = point_step_px;
  readValue(source, section, "point_step_px", step);
  if (step < 1) THROW_EXCEPTION_FMT("[%s] point_step_px must be >= 1, got %d", section.c_str(), step);
  style = new_style;
  point_step_px = step;
}

void CSuperpixelMap::TRenderOptions::saveToConfigFile(mrpt::config::CConfigFileBase& target,
                                                      const std::string& section) const {
  target.write(section, "style", std::string(style == Style::discs ? "discs" : "points"));
  target.write(section, "point_step_px", point_step_px);
}

// ---- Map definition: [<prefix>_creationOpts], [<prefix>_likelihoodOpts], [<prefix>_renderOpts].

CSuperpixelMap::TMapDefinition::TMapDefinition() = default;

void CSuperpixelMap::TMapDefinition::loadFromConfigFile_map_specific(const mrpt::config::CConfigFileBase& source,
                                                                     const std::string& prefix) {
  creationOpts.loadFromConfigFile(source, prefix + "_creationOpts");
  likelihoodOpts.loadFromConfigFile(source, prefix + "_likelihoodOpts");
  renderOpts.loadFromConfigFile(source, prefix + "_renderOpts");
}

void CSuperpixelMap::TMapDefinition::dumpToTextStream_map_specific(std::ostream& out) const {
  mrpt::config::CConfigFileMemory mem;
  creationOpts.saveToConfigFile(mem, "creationOpts");
  likelihoodOpts.saveToConfigFile(mem, "likelihoodOpts");
  renderOpts.saveToConfigFile(mem, "renderOpts");
  out << mem.getContent();
}

mrpt::maps::CMetricMap* CSuperpixelMap::internal_CreateFromMapDefinition(
    const mrpt::maps::TMetricMapInitializer& definition) {
  const auto* def = dynamic_cast<const CSuperpixelMap::TMapDefinition*>(&definition);
  if (!def) THROW_EXCEPTION("gasp::CSuperpixelMap: the map definition is not a CSuperpixelMap::TMapDefinition");
  auto map = std::make_unique<CSuperpixelMap>();
  map->creationOptions = def->creationOpts;
  map->likelihoodOptions = def->likelihoodOpts;
  map->renderOptions = def->renderOpts;
  return map.release();  // MRPT's map factory takes ownership
}

}  // namespace gasp
