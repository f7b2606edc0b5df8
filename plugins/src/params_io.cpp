#include "gasp/mrpt/params_io.h"

#include <mrpt/core/exceptions.h>

#include <cctype>
#include <cmath>
#include <cstdint>
#include <vector>

#include "gasp/core/error.h"
#include "gasp/superpixels/depth_superpixels.h"

namespace gasp {

namespace {

// ---- Key tables: each calls f(key, field) for every field of the struct.

template <class P, class F>
void superpixelFields(P& p, F&& f) {
  f("discontinuity_abs_m", p.discontinuity_abs_m);
  f("discontinuity_rel", p.discontinuity_rel);
  f("normal_window_px_per_m", p.normal_window_px_per_m);
  f("normal_min_radius_px", p.normal_min_radius_px);
  f("normal_max_radius_px", p.normal_max_radius_px);
  f("max_crease_angle_deg", p.max_crease_angle_deg);
  f("max_neighbour_normal_angle_deg", p.max_neighbour_normal_angle_deg);
  f("min_component_pixels", p.min_component_pixels);
  f("target_patch_area_m2", p.target_patch_area_m2);
  f("kmeans_iterations", p.kmeans_iterations);
  f("kmeans_normal_weight", p.kmeans_normal_weight);
  f("seed_sampling_step_px", p.seed_sampling_step_px);
  f("seed", p.seed);
  f("max_incidence_deg", p.max_incidence_deg);
  f("min_patch_pixels", p.min_patch_pixels);
  f("min_patch_area_ratio", p.min_patch_area_ratio);
  f("regrow_normal_weight_m", p.regrow_normal_weight_m);
  f("processing_step_px", p.processing_step_px);
  f("kmeans_iteration_step_px", p.kmeans_iteration_step_px);
  f("kmeans_coarse_iterations", p.kmeans_coarse_iterations);
}

template <class P, class F>
void pairFields(P& p, F&& f) {
  f("target_patch_area_m2", p.superpixels.target_patch_area_m2);
  f("neighbourhood_k", p.association.feature_sets.neighbourhood.k);
  f("candidates", p.association.candidates);
  f("lambda", p.association.lambda);
  f("mutual_check", p.association.mutual_check);
  f("min_inliers", p.pose.ransac.min_inliers);
  f("dense_rounds", p.dense_rounds);
  f("dense_max_rounds", p.dense_max_rounds);
  f("dense_converged_m", p.dense_converged_m);
  f("dense_extrapolation_max", p.dense_extrapolation_max);
  f("dense_line_search", p.dense_line_search);
  f("dense_line_search_halvings", p.dense_line_search_halvings);
  f("refine", p.refine);
  f("retry_area_factor", p.retry_area_factor);
  f("slide_scan", p.slide_scan.enabled);
  f("model_error_t_m", p.model_error.sigma_t_m);
  f("model_error_r_deg", p.model_error.sigma_r_deg);
}

// ---- Strict text parsing (MRPT's read_double() would turn "abc" into 0 silently).

std::string trimmed(const std::string& s) {
  std::size_t b = 0, e = s.size();
  while (b < e && std::isspace(static_cast<unsigned char>(s[b]))) ++b;
  while (e > b && std::isspace(static_cast<unsigned char>(s[e - 1]))) --e;
  return s.substr(b, e - b);
}

bool parse(const std::string& text, double& v) {
  try {
    std::size_t used = 0;
    const double x = std::stod(text, &used);
    if (used != text.size() || !std::isfinite(x)) return false;
    v = x;
    return true;
  } catch (const std::exception&) {
    return false;
  }
}

bool parse(const std::string& text, int& v) {
  try {
    std::size_t used = 0;
    const long x = std::stol(text, &used);
    if (used != text.size() || x < INT32_MIN || x > INT32_MAX) return false;
    v = static_cast<int>(x);
    return true;
  } catch (const std::exception&) {
    return false;
  }
}

bool parse(const std::string& text, std::uint64_t& v) {
  if (text.empty() || text[0] == '-') return false;
  try {
    std::size_t used = 0;
    const unsigned long long x = std::stoull(text, &used);
    if (used != text.size()) return false;
    v = x;
    return true;
  } catch (const std::exception&) {
    return false;
  }
}

bool parse(const std::string& text, bool& v) {
  std::string t;
  for (char c : text) t += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (t == "true" || t == "1" || t == "yes" || t == "on") return v = true, true;
  if (t == "false" || t == "0" || t == "no" || t == "off") return v = false, true;
  return false;
}

const char* typeName(const double&) { return "a finite number"; }
const char* typeName(const int&) { return "an integer"; }
const char* typeName(const std::uint64_t&) { return "a non-negative integer"; }
const char* typeName(const bool&) { return "true or false"; }

std::string toText(double v) { return mrpt::format("%.17g", v); }
std::string toText(int v) { return std::to_string(v); }
std::string toText(std::uint64_t v) { return std::to_string(v); }
std::string toText(bool v) { return v ? "true" : "false"; }

template <class T>
void readOne(const mrpt::config::CConfigFileBase& source, const std::string& section, const std::string& key, T& field) {
  if (!source.keyExists(section, key)) return;
  const std::string text = trimmed(source.read_string(section, key, ""));
  if (!parse(text, field)) {
    THROW_EXCEPTION_FMT("[%s] %s = '%s': expected %s", section.c_str(), key.c_str(), text.c_str(), typeName(field));
  }
}

/// Reads the keys of `table` from an ini section; unknown keys (except `other_allowed`) throw.
template <class Table>
void readIni(const mrpt::config::CConfigFileBase& source, const std::string& section, Table&& table,
             const std::set<std::string>& other_allowed) {
  std::set<std::string> known = other_allowed;
  table([&](const char* key, auto& field) {
    known.insert(key);
    readOne(source, section, key, field);
  });
  checkKeys(source, section, known);
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
    THROW_EXCEPTION_FMT("[%s]: invalid parameters: %s", section.c_str(), e.what());
  }
  params = p;
}

void readPairParams(const mrpt::containers::yaml& y, const std::string& who, PairParams& params) {
  PairParams p = params;
  if (!y.isNullNode() && !y.empty()) {
    if (!y.isMap()) THROW_EXCEPTION_FMT("%s: parameters must be a YAML map", who.c_str());
    std::set<std::string> known;
    pairFields(p, [&](const char* key, auto& field) {
      known.insert(key);
      if (!y.has(key)) return;
      using T = std::decay_t<decltype(field)>;
      try {
        field = y[key].template as<T>();
      } catch (const std::exception&) {
        THROW_EXCEPTION_FMT("%s: parameter '%s' must be %s", who.c_str(), key, typeName(field));
      }
    });
    for (const auto& [key, value] : y.asMap()) {
      const auto name = key.as<std::string>();
      if (!known.count(name)) THROW_EXCEPTION_FMT("%s: unknown parameter '%s'", who.c_str(), name.c_str());
    }
  }
  try {
    validate(p);
  } catch (const Error& e) {
    THROW_EXCEPTION_FMT("%s: invalid parameters: %s", who.c_str(), e.what());
  }
  params = p;
}

void writePairParams(const PairParams& params, mrpt::config::CConfigFileBase& target, const std::string& section) {
  pairFields(params, [&](const char* key, const auto& v) { target.write(section, key, toText(v)); });
}

}  // namespace gasp
