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
template <class Apply>
std::string keysInvalidAlone(const std::vector<std::string>& keys, const PairParams& base, Apply&& apply) {
  std::string out;
  for (const std::string& key : keys) {
    PairParams trial = base;
    try {
      apply(key, trial);
      validate(trial);
    } catch (const std::exception&) {
      out += (out.empty() ? " (key " : ", ") + key;
    }
  }
  return out.empty() ? out : out + ")";
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
  readIni(source, section, [&](auto&& f) { superpixelFields(p, f); }, other_allowed_keys);
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

void readPairParams(const mrpt::config::CConfigFileBase& source, const std::string& section, PairParams& params,
                    const std::set<std::string>& other_allowed_keys) {
  PairParams p = params;
  readIni(source, section, [&](auto&& f) { pairFields(p, f); }, other_allowed_keys);
  try {
    validate(p);
  } catch (const Error& e) {
    // Name the keys that are invalid on their own: the stages' messages name their fields.
    std::vector<std::string> keys;
    source.getAllKeys(section, keys);
    const std::string culprits = keysInvalidAlone(keys, params, [&](const std::string& key, PairParams& trial) {
      if (other_allowed_keys.count(key)) return;
      mrpt::config::CConfigFileMemory one;
      one.write(section, key, source.read_string(section, key, ""));
      pairFields(trial, [&](const char* k, auto&& field) {
        if (key == k) readOne(one, section, k, std::forward<decltype(field)>(field));
      });
    });
    THROW_EXCEPTION_FMT("[%s]: invalid parameters%s: %s", section.c_str(), culprits.c_str(), e.what());
  }
  params = p;
}

void readPairParams(const mrpt::containers::yaml& y, const std::string& who, PairParams& params) {
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
  pairFields(params, [&](const char* key, const auto& v) { target.write(section, key, toText(v)); });
}

}  // namespace gasp
