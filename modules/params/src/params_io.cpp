#include "gasp/params/params_io.h"

#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/core/exceptions.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "gasp/core/error.h"
#include "gasp/params/params_file.h"
#include "gasp/superpixels/depth_superpixels.h"
#include "param_keys.h"

namespace gasp {

namespace {

using namespace detail;

/// Reads the keys of `table` from an ini section; unknown keys (except `other_allowed`) throw.
template <class Table>
void readIni(const mrpt::config::CConfigFileBase& source, const std::string& section, Table&& table,
             const std::set<std::string>& other_allowed) {
  std::set<std::string> known = other_allowed;
  table([&](const char* key, auto&& field) {
    known.insert(key);
    readOne(source, section, key, std::forward<decltype(field)>(field));
  });
  checkKeys(source, section, known);
}

/// " (key K1, K2)": the keys of `keys` that make `base` invalid when set alone (`apply` sets one
/// on a copy), or "" when none does (only their combination is invalid).
template <class P, class Apply>
std::string keysInvalidAlone(const std::vector<std::string>& keys, const P& base, Apply&& apply) {
  std::string out;
  for (const std::string& key : keys) {
    P trial = base;
    try {
      apply(key, trial);
      validate(trial);
    } catch (const std::exception&) {
      out += (out.empty() ? " (key " : ", ") + key;
    }
  }
  return out.empty() ? out : out + ")";
}

/// With a `params_file = PATH` key in the section, `params` read over by that params file first
/// (`part` maps the file's SlamParams to the section's part of it, both ways), so that an MRPT ini
/// and every program share one file; the section's own keys then override it.
template <class Part>
void loadParamsFileKey(const mrpt::config::CConfigFileBase& source, const std::string& section, Part&& part) {
  if (!source.keyExists(section, "params_file")) return;
  const std::string path = trimmed(source.read_string(section, "params_file", ""));
  try {
    SlamParams all;
    part(all, false);  // the section's values into `all`
    all = readParamsFile(path, all);
    part(all, true);  // and back
  } catch (const Error& e) {
    THROW_EXCEPTION_FMT("[%s] params_file: %s", section.c_str(), e.what());
  }
}

/// part(all, back) for loadParamsFileKey: `field` of the file's parameters is `params`.
template <class P, class Field>
auto partOf(P& params, Field&& field) {
  return [&params, field](SlamParams& all, bool back) {
    if (back) params = field(all);
    else field(all) = params;
  };
}

/// Reads the keys `fields(p, f)` lists from an ini section over `params`, then validates them;
/// unknown keys (except `other_allowed`) and invalid values throw naming the section and key.
template <class P, class Fields>
void readSection(const mrpt::config::CConfigFileBase& source, const std::string& section, P& params,
                 std::set<std::string> other_allowed, Fields&& fields) {
  other_allowed.insert("params_file");  // read by the caller (loadParamsFileKey)
  P p = params;
  readIni(source, section, [&](auto&& f) { fields(p, f); }, other_allowed);
  try {
    validate(p);
  } catch (const Error& e) {
    // Name the keys that are invalid on their own: the stages' messages name their fields.
    std::vector<std::string> keys;
    source.getAllKeys(section, keys);
    const std::string culprits = keysInvalidAlone(keys, params, [&](const std::string& key, P& trial) {
      if (other_allowed.count(key)) return;
      mrpt::config::CConfigFileMemory one;
      one.write(section, key, source.read_string(section, key, ""));
      fields(trial, [&](const char* k, auto&& field) {
        if (key == k) readOne(one, section, k, std::forward<decltype(field)>(field));
      });
    });
    THROW_EXCEPTION_FMT("[%s]: invalid parameters%s: %s", section.c_str(), culprits.c_str(), e.what());
  }
  params = p;
}

template <class P, class Fields>
void writeSection(const P& params, mrpt::config::CConfigFileBase& target, const std::string& section, Fields&& fields) {
  fields(params, [&](const char* key, const auto& v) { target.write(section, key, toText(v)); });
}

/// The loop closer's section: the pair's keys and the loop closer's own.
struct LoopClosureSection {
  PairParams pair;
  LoopClosureParams loop;
};
void validate(const LoopClosureSection& s) {
  validate(s.pair);
  validate(s.loop);
}

}  // namespace

void readValue(const mrpt::config::CConfigFileBase& source, const std::string& section, const std::string& key,
               double& value) {
  readOne(source, section, key, value);
}

void readValue(const mrpt::config::CConfigFileBase& source, const std::string& section, const std::string& key,
               int& value) {
  readOne(source, section, key, value);
}

void readValue(const mrpt::config::CConfigFileBase& source, const std::string& section, const std::string& key,
               bool& value) {
  readOne(source, section, key, value);
}

void writeValue(mrpt::config::CConfigFileBase& target, const std::string& section, const std::string& key,
                double value) {
  target.write(section, key, toText(value));
}

void checkKeys(const mrpt::config::CConfigFileBase& source, const std::string& section,
               const std::set<std::string>& known) {
  if (!source.sectionExists(section)) return;
  std::vector<std::string> keys;
  source.getAllKeys(section, keys);
  for (const auto& k : keys) {
    if (known.count(k)) continue;
    std::string list;
    for (const auto& n : known) list += (list.empty() ? "" : ", ") + n;
    THROW_EXCEPTION_FMT("[%s]: unknown key '%s' (known keys: %s)", section.c_str(), k.c_str(), list.c_str());
  }
}

void readSuperpixelParams(const mrpt::config::CConfigFileBase& source, const std::string& section,
                          SuperpixelParams& params, const std::set<std::string>& other_allowed_keys) {
  SuperpixelParams p = params;
  loadParamsFileKey(source, section,
                    partOf(p, [](SlamParams& all) -> SuperpixelParams& { return all.odometry.pair.segment; }));
  std::set<std::string> allowed = other_allowed_keys;
  allowed.insert("params_file");
  readIni(source, section, [&](auto&& f) { superpixelFields(p, f); }, allowed);
  try {
    validate(p);
  } catch (const Error& e) {
    THROW_EXCEPTION_FMT("[%s]: %s", section.c_str(), e.what());
  }
  params = p;
}

void writeSuperpixelParams(const SuperpixelParams& params, mrpt::config::CConfigFileBase& target,
                           const std::string& section) {
  superpixelFields(params, [&](const char* key, const auto& v) { target.write(section, key, toText(v)); });
}

void readLidarParams(const mrpt::config::CConfigFileBase& source, const std::string& section, LidarParams& params,
                     const std::set<std::string>& other_allowed_keys) {
  LidarParams p = params;  // unchanged when reading fails
  loadParamsFileKey(source, section, partOf(p, [](SlamParams& all) -> LidarParams& { return all.lidar; }));
  readSection(source, section, p, other_allowed_keys, [](auto& q, auto&& f) { lidarFields(q, f); });
  params = p;
}

void writeLidarParams(const LidarParams& params, mrpt::config::CConfigFileBase& target, const std::string& section) {
  writeSection(params, target, section, [](auto& p, auto&& f) { lidarFields(p, f); });
}

std::set<std::string> superpixelKeys() {
  std::set<std::string> keys;
  SuperpixelParams p;
  superpixelFields(p, [&](const char* key, auto&&) { keys.insert(key); });
  return keys;
}

std::set<std::string> pairKeys() {
  std::set<std::string> keys;
  PairParams p;
  pairFields(p, [&](const char* key, auto&&) { keys.insert(key); });
  return keys;
}

std::set<std::string> lidarKeys() {
  std::set<std::string> keys;
  LidarParams p;
  lidarFields(p, [&](const char* key, auto&&) { keys.insert(key); });
  return keys;
}

void readPairParams(const mrpt::config::CConfigFileBase& source, const std::string& section, PairParams& params,
                    const std::set<std::string>& other_allowed_keys) {
  PairParams p = params;  // unchanged when reading fails
  loadParamsFileKey(source, section, partOf(p, [](SlamParams& all) -> PairParams& { return all.odometry.pair; }));
  readSection(source, section, p, other_allowed_keys, [](auto& q, auto&& f) { pairFields(q, f); });
  params = p;
}

void readOdometryParams(const mrpt::config::CConfigFileBase& source, const std::string& section,
                        OdometryParams& params, const std::set<std::string>& other_allowed_keys) {
  OdometryParams p = params;  // unchanged when reading fails
  loadParamsFileKey(source, section, partOf(p, [](SlamParams& all) -> OdometryParams& { return all.odometry; }));
  readSection(source, section, p, other_allowed_keys, [](auto& q, auto&& f) {
    pairFields(q.pair, f);
    odometryFields(q, f);
  });
  params = p;
}

void writeOdometryParams(const OdometryParams& params, mrpt::config::CConfigFileBase& target,
                         const std::string& section) {
  writeSection(params, target, section, [](auto& p, auto&& f) {
    pairFields(p.pair, f);
    odometryFields(p, f);
  });
}

void readLoopClosureParams(const mrpt::config::CConfigFileBase& source, const std::string& section, PairParams& pair,
                           LoopClosureParams& loop, const std::set<std::string>& other_allowed_keys) {
  LoopClosureSection s{pair, loop};
  loadParamsFileKey(source, section, [&s](SlamParams& all, bool back) {
    if (back) {
      s = {all.odometry.pair, all.loop};
    } else {
      all.odometry.pair = s.pair;
      all.loop = s.loop;
    }
  });
  readSection(source, section, s, other_allowed_keys, [](auto& p, auto&& f) {
    pairFields(p.pair, f);
    loopClosureFields(p.loop, f);
  });
  pair = s.pair;
  loop = s.loop;
}

void writeLoopClosureParams(const PairParams& pair, const LoopClosureParams& loop, mrpt::config::CConfigFileBase& target,
                            const std::string& section) {
  writeSection(pair, target, section, [](auto& p, auto&& f) { pairFields(p, f); });
  writeSection(loop, target, section, [](auto& p, auto&& f) { loopClosureFields(p, f); });
}

void readPoseGraphSettings(const mrpt::config::CConfigFileBase& source, const std::string& section,
                           PoseGraphSettings& settings, const std::set<std::string>& other_allowed_keys) {
  PoseGraphSettings p = settings;  // unchanged when reading fails
  loadParamsFileKey(source, section, partOf(p, [](SlamParams& all) -> PoseGraphSettings& { return all.graph; }));
  readSection(source, section, p, other_allowed_keys, [](auto& q, auto&& f) { poseGraphFields(q, f); });
  settings = p;
}

void writePoseGraphSettings(const PoseGraphSettings& settings, mrpt::config::CConfigFileBase& target,
                            const std::string& section) {
  writeSection(settings, target, section, [](auto& p, auto&& f) { poseGraphFields(p, f); });
}

namespace {

/// A YAML node in the params file's form: a map with a section (segment, associate, ...) or a
/// `params_file` key, rather than the flat keys.
bool paramsFileForm(const mrpt::containers::yaml& y) {
  if (!y.isMap()) return false;
  const auto& sections = paramsSections();
  for (const auto& [key, value] : y.asMap()) {
    const auto name = key.as<std::string>();
    if (name == "params_file" || std::find(sections.begin(), sections.end(), name) != sections.end()) return true;
  }
  return false;
}

}  // namespace

void readPairParams(const mrpt::containers::yaml& y, const std::string& who, PairParams& params, LidarParams* lidar) {
  if (paramsFileForm(y)) {
    // The params file's form: `params_file: PATH` (loaded first) and sections over it; the
    // sections a pair does not use (odometry, loop_closure, pose_graph) are read and checked too,
    // so that one file serves every program and the matcher.
    try {
      SlamParams p;
      p.odometry.pair = params;
      if (lidar) p.lidar = *lidar;
      mrpt::containers::yaml sections = mrpt::containers::yaml::Map();
      for (const auto& [key, value] : y.asMap()) {
        const auto name = key.as<std::string>();
        if (name == "params_file") {
          p = readParamsFile(mrpt::containers::yaml(value).as<std::string>(), p);
        } else if (paramsKeys(name).empty()) {
          throw Error("'" + name + "' is neither a section nor params_file (the flat keys cannot be mixed with sections)");
        } else {
          sections[name] = mrpt::containers::yaml(value);
        }
      }
      const SlamParams read = readParamsNode(sections, "parameters", p);
      params = read.odometry.pair;
      if (lidar) *lidar = read.lidar;
    } catch (const Error& e) {
      THROW_EXCEPTION_FMT("%s: %s", who.c_str(), e.what());
    }
    return;
  }
  PairParams p = params;
  if (!y.isNullNode() && !y.empty()) {
    if (!y.isMap()) THROW_EXCEPTION_FMT("%s: parameters must be a YAML map", who.c_str());
    std::set<std::string> known;
    pairFields(p, [&](const char* key, auto&& field) {
      known.insert(key);
      if (!y.has(key)) return;
      if (!fromYaml(y[key], std::forward<decltype(field)>(field)))
        THROW_EXCEPTION_FMT("%s: parameter '%s' must be %s", who.c_str(), key, typeName(field));
    });
    for (const auto& [key, value] : y.asMap()) {
      const auto name = key.as<std::string>();
      if (!known.count(name)) THROW_EXCEPTION_FMT("%s: unknown parameter '%s'", who.c_str(), name.c_str());
    }
  }
  try {
    validate(p);
  } catch (const Error& e) {
    std::vector<std::string> keys;
    for (const auto& [key, value] : y.asMap()) keys.push_back(key.as<std::string>());
    const std::string culprits = keysInvalidAlone(keys, params, [&](const std::string& key, PairParams& trial) {
      pairFields(trial, [&](const char* k, auto&& field) {
        if (key == k) fromYaml(y[k], std::forward<decltype(field)>(field));
      });
    });
    THROW_EXCEPTION_FMT("%s: invalid parameters%s: %s", who.c_str(), culprits.c_str(), e.what());
  }
  params = p;
}

void writePairParams(const PairParams& params, mrpt::config::CConfigFileBase& target, const std::string& section) {
  writeSection(params, target, section, [](auto& p, auto&& f) { pairFields(p, f); });
}

}  // namespace gasp
