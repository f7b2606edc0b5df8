#pragma once
/// \file param_keys.h (private) The key of every parameter, one table per section of the params
/// file (params_file.h) and, concatenated, the flat key list of an ini section (params_io.h);
/// strict text parsing of one value and its exact text. Each table calls f(key, field) for every
/// field, so that reading and writing cover every parameter.
#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/containers/yaml.h>
#include <mrpt/core/exceptions.h>
#include <mrpt/core/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "gasp/pipeline/pair_registration.h"
#include "gasp/slam/slam_params.h"
#include "gasp/superpixels/superpixel_params.h"

namespace gasp::detail {

// ---- Key tables: each calls f(key, field) for every field of the struct, so that reading and
// writing (and with them the maps' serialization) cover every parameter. A field that may be
// infinite is passed as MayBeInfinite.

template <class D>
struct MayBeInfinite {
  D& value;  ///< double or const double; +inf allowed, NaN and -inf not
};
template <class D>
MayBeInfinite(D&) -> MayBeInfinite<D>;

template <class P, class F>
void superpixelFields(P& p, F&& f) {
  f("discontinuity_abs_m", p.surfaces.discontinuity_abs_m);
  f("discontinuity_rel", p.surfaces.discontinuity_rel);
  f("normal_window_px_per_m", p.surfaces.normal_window_px_per_m);
  f("normal_min_radius_px", p.surfaces.normal_min_radius_px);
  f("normal_max_radius_px", p.surfaces.normal_max_radius_px);
  f("max_crease_angle_deg", p.surfaces.max_crease_angle_deg);
  f("max_neighbour_normal_angle_deg", p.surfaces.max_neighbour_normal_angle_deg);
  f("min_component_pixels", p.surfaces.min_component_pixels);
  f("target_patch_area_m2", p.target_patch_area_m2);
  f("kmeans_iterations", p.kmeans.kmeans_iterations);
  f("kmeans_normal_weight", p.kmeans.kmeans_normal_weight);
  f("seed_sampling_step_px", p.kmeans.seed_sampling_step_px);
  f("seed", p.kmeans.seed);
  f("max_incidence_deg", p.max_incidence_deg);
  f("min_patch_pixels", p.cleanup.min_patch_pixels);
  f("min_patch_area_ratio", p.cleanup.min_patch_area_ratio);
  f("regrow_normal_weight_m", p.cleanup.regrow_normal_weight_m);
  f("processing_step_px", p.processing_step_px);
  f("kmeans_iteration_step_px", p.kmeans.kmeans_iteration_step_px);
  f("kmeans_coarse_iterations", p.kmeans.kmeans_coarse_iterations);
  f("crease_borders", p.borders.crease_borders);
  f("crease_min_angle_deg", p.borders.crease_min_angle_deg);
  f("crease_band_px", p.borders.crease_band_px);
  f("plane_noise_abs_m", p.borders.plane_noise_abs_m);
  f("plane_noise_rel", p.borders.plane_noise_rel);
  f("step_borders", p.borders.step_borders);
  f("step_min_sigmas", p.borders.step_min_sigmas);
  f("step_smoothness", p.borders.step_smoothness);
}

/// The pair pipeline by stage (pair_registration.h), one table per section of the params file.
template <class P, class F>
void associateFields(P& p, F&& f) {  // associate_stage.h, view_association.h
  auto& a = p.associate;
  f("neighbourhood_k", a.feature_sets.neighbourhood.k);
  f("feature_e_theta_rad", a.feature_sets.feature.e_theta_rad);
  f("feature_min_separation_m", a.feature_sets.feature.min_separation_m);
  f("ordering_e_r_m", a.feature_sets.ordering.e_r_m);
  f("ordering_e_theta_rad", a.feature_sets.ordering.e_theta_rad);
  f("r_dev_m", a.match.r_dev_m);
  f("theta_dev_rad", a.match.theta_dev_rad);
  f("cost_insert", a.costs.insert);
  f("cost_delete", a.costs.del);
  f("cost_replace", MayBeInfinite{a.costs.replace});
  f("cost_transpose", MayBeInfinite{a.costs.transpose});
  f("candidates", a.candidates);
  f("lambda", a.lambda);
  f("mutual_check", a.mutual_check);
  f("candidate_key", a.candidate_key);
  f("distinctiveness_ratio", a.distinctiveness_ratio);
}

template <class P, class F>
void hypothesiseFields(P& p, F&& f) {  // RANSAC (ransac.h), the patch refinement (refinement.h), guided verification
  auto& r = p.hypothesise.pose.ransac;
  f("inlier_distance_m", r.inlier.distance_m);
  f("inlier_normal_angle_deg", r.inlier.normal_angle_deg);
  f("ransac_edge_tolerance_m", r.edge_tolerance_m);
  f("ransac_normal_pair_tolerance_deg", r.normal_pair_tolerance_deg);
  f("ransac_min_triangle_height_m", r.min_triangle_height_m);
  f("min_inliers", r.min_inliers);
  f("ransac_max_iterations", r.max_iterations);
  f("ransac_confidence", r.confidence);
  f("ransac_seed", r.seed);
  f("ransac_guided_sampling", r.guided_sampling);
  f("ransac_min_iterations", r.min_iterations);
  f("ransac_max_guided_correspondences", r.max_guided_correspondences);
  auto& q = p.hypothesise.pose.refinement;
  f("refine", p.hypothesise.pose.refine);
  f("refinement_loss", q.loss);
  f("refinement_loss_scale_m", q.loss_scale_m);
  f("refinement_bidirectional", q.bidirectional);
  f("refinement_max_iterations", q.max_iterations);
  f("refinement_solver", q.solver);
  f("refinement_noise_sigma_m", q.noise_sigma_m);
  f("refinement_degeneracy_min_eigenvalue_ratio", q.degeneracy.min_eigenvalue_ratio);
  f("refinement_degeneracy_max_std_m", q.degeneracy.max_std_m);
  f("refinement_reselection_rounds", p.hypothesise.pose.reselection_rounds);
  auto& g = p.hypothesise.guided;
  f("guided_verification", g.enabled);
  f("guided_densify", g.densify);
  f("guided_max_distance_m", g.gates.max_distance_m);
  f("guided_max_normal_angle_deg", g.gates.max_normal_angle_deg);
  f("guided_lambda", g.gates.lambda);
  f("min_guided_support", g.min_support);
}

template <class P, class F>
void refineFields(P& p, F&& f) {  // dense rounds (dense_rounds.h), pixel and edge terms, the solver, the slide scan
  auto& d = p.refine;
  f("dense_rounds", d.dense.rounds);
  f("dense_gates_m", d.dense.gates_m);
  f("dense_max_rounds", d.dense.max_rounds);
  f("dense_converged_m", d.dense.converged_m);
  f("dense_extrapolation_max", d.dense.extrapolation_max);
  f("dense_line_search", d.dense.line_search);
  f("dense_line_search_halvings", d.dense.line_search_halvings);
  f("projective_pixel_step", d.pixels.pixel_step);
  f("projective_max_distance_m", d.pixels.max_distance_m);
  f("projective_max_normal_angle_deg", d.pixels.max_normal_angle_deg);
  f("projective_pixel_footprint", d.pixels.pixel_footprint);
  f("projective_sample_spacing_deg", d.pixels.sample_spacing_deg);
  f("edge_terms", d.edges.enabled);
  f("edge_min_jump_m", d.edges.terms.min_jump_m);
  f("edge_jump_per_m2", d.edges.terms.jump_per_m2);
  f("edge_pixel_step", d.edges.terms.pixel_step);
  f("edge_line_neighbours", d.edges.terms.line_neighbours);
  f("edge_max_distance_m", d.edges.terms.max_distance_m);
  f("edge_weight", d.edges.terms.weight);
  f("wide_edge_gate_factor", d.edges.wide_gate_factor);
  f("wide_edge_min_paired_share", d.edges.wide_min_paired_share);
  f("dense_loss", d.solver.loss);
  f("dense_loss_scale_m", d.solver.loss_scale_m);
  f("dense_bidirectional", d.solver.bidirectional);
  f("dense_max_iterations", d.solver.max_iterations);
  f("dense_solver", d.solver.solver);
  f("dense_noise_sigma_m", d.solver.noise_sigma_m);
  f("dense_degeneracy_min_eigenvalue_ratio", d.solver.degeneracy.min_eigenvalue_ratio);
  f("dense_degeneracy_max_std_m", d.solver.degeneracy.max_std_m);
  f("slide_scan", d.slide_scan.enabled);
  f("slide_scan_range_m", d.slide_scan.range_m);
  f("slide_scan_step_m", d.slide_scan.step_m);
  f("slide_scan_min_gain", d.slide_scan.min_gain);
  f("slide_scan_pixel_step", d.slide_scan.pixel_step);
}

template <class P, class F>
void certifyFields(P& p, F&& f) {  // the views' degeneracy, dense support, free space (visibility_check.h), model error, uniqueness
  auto& c = p.certify;
  f("view_degeneracy_min_eigenvalue_ratio", c.view_degeneracy.min_eigenvalue_ratio);
  f("partial_poses", c.partial_poses);
  f("min_dense_terms", c.min_dense_terms);
  f("visibility_pixel_step", c.visibility.pixel_step);
  f("visibility_gate_m", c.visibility.gate_m);
  f("visibility_gate_per_m2", c.visibility.gate_per_m2);
  f("visibility_pixel_spread", c.visibility.pixel_spread);
  f("visibility_max_violation_ratio", c.visibility.max_violation_ratio);
  f("visibility_max_occluded_ratio", c.visibility.max_occluded_ratio);
  f("visibility_max_two_way_violation_ratio", c.visibility.max_two_way_violation_ratio);
  f("visibility_min_consistent", c.visibility.min_consistent);
  f("one_way_max_violation_ratio", c.fallback_max_violation_ratio);
  f("model_error_t_m", c.model_error.sigma_t_m);
  f("model_error_r_deg", c.model_error.sigma_r_deg);
  f("min_likelihood_ratio", c.min_likelihood_ratio);
  f("likelihood_violation_nats", c.violation_nats);
  f("symmetry_test", c.symmetry_test);
}

template <class P, class F>
void retryFields(P& p, F&& f) {  // retry_stage.h
  f("one_way_fallback", p.retry.one_way_fallback);
  f("retry_area_factor", p.retry.finer_area_factor);
}

/// The pair pipeline: its segmentation (the matcher's observations, the finer-scale retry) under
/// the segmentation's keys, then every stage's parameters: the flat key list of an ini section.
template <class P, class F>
void pairFields(P& p, F&& f) {
  superpixelFields(p.segment, f);
  associateFields(p, f);
  hypothesiseFields(p, f);
  refineFields(p, f);
  certifyFields(p, f);
  retryFields(p, f);
}

/// The odometry's own keys (odometry_params.h; scene_change_X = SceneChangeParams::X).
template <class P, class F>
void odometryFields(P& p, F&& f) {
  f("keyframe_distance_m", p.keyframe_distance_m);
  f("keyframe_angle_deg", p.keyframe_angle_deg);
  f("max_speed_mps", p.max_speed_mps);
  f("max_rate_radps", p.max_rate_radps);
  f("rolling_shutter_readout_s", p.rolling_shutter_readout_s);
  f("deskew_sweeps", p.deskew_sweeps);
  f("tracking", p.tracking);
  auto& s = p.scene_change;
  f("scene_change", s.enabled);
  f("scene_change_max_violation_ratio", s.max_violation_ratio);
  f("scene_change_max_two_way_violation_ratio", s.max_two_way_violation_ratio);
  f("scene_change_max_occluded_ratio", s.max_occluded_ratio);
  f("scene_change_gate_m", s.gate_m);
  f("scene_change_gate_deg", s.gate_deg);
  f("scene_change_max_accel_mps2", s.max_accel_mps2);
  f("scene_change_max_angular_accel_radps2", s.max_angular_accel_radps2);
  f("scene_change_max_gate_m", s.max_gate_m);
  f("scene_change_max_gate_deg", s.max_gate_deg);
}

/// The loop closer (slam_params.h); its inlier count is loop_min_inliers beside RANSAC's min_inliers.
template <class P, class F>
void loopClosureFields(P& p, F&& f) {
  f("enabled", p.enabled);
  f("search_radius_m", p.search_radius_m);
  f("max_axis_angle_deg", p.max_axis_angle_deg);
  f("min_keyframe_gap", p.min_keyframe_gap);
  f("max_candidates", p.max_candidates);
  f("loop_min_inliers", p.min_inliers);
  f("gate_chi2", p.gate_chi2);
  f("relocalisation_candidates", p.relocalisation_candidates);
  f("relocalisation_min_inliers", p.relocalisation_min_inliers);
  f("relocalisation_agreeing", p.relocalisation_agreeing);
  f("background", p.background);
  f("loop_search", p.search);
  f("retrieval_candidates", p.retrieval_candidates);
}

/// A rotating LiDAR's sweeps (range_view.h).
template <class P, class F>
void lidarFields(P& p, F&& f) {
  f("patch_area_m2", p.patch_area_m2);
  f("range_sigma_m", p.range_sigma_m);
  f("returns_column_step", p.returns_column_step);
  f("returns_look_up_columns", p.returns_look_up_columns);
  f("returns_max_rounds", p.returns_max_rounds);
  f("returns_converged_m", p.returns_converged_m);
  f("returns_normal_half_width", p.returns_normal_half_width);
  f("returns_max_flatness", p.returns_max_flatness);
  f("returns_normal_growth", p.returns_normal_growth);
  f("sweep_symmetry_test", p.symmetry_test);
  f("sweep_violation_nats", p.violation_nats);
  f("dense_sample_spacing_deg", p.dense_sample_spacing_deg);
  f("ground_search", p.ground_search);
  f("ground_search_max_offset_m", p.ground_search_max_offset_m);
  f("sweep_motion", p.sweep_motion);
  f("sweep_speed_sigma_mps", p.sweep_speed_sigma_mps);
  f("sweep_rate_sigma_radps", p.sweep_rate_sigma_radps);
}

/// The pose-graph optimiser (pose_graph_optimizer.h).
template <class P, class F>
void poseGraphFields(P& p, F&& f) {
  f("max_iterations", p.max_iterations);
  f("function_tolerance", p.function_tolerance);
  f("num_threads", p.num_threads);
}

// ---- Strict text parsing (MRPT's read_double() would turn "abc" into 0 silently).

inline std::string trimmed(const std::string& s) {
  std::size_t b = 0, e = s.size();
  while (b < e && std::isspace(static_cast<unsigned char>(s[b]))) ++b;
  while (e > b && std::isspace(static_cast<unsigned char>(s[e - 1]))) --e;
  return s.substr(b, e - b);
}

inline bool parse(const std::string& text, double& v) {
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

inline bool parse(const std::string& text, int& v) {
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

inline bool parse(const std::string& text, std::uint64_t& v) {
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

inline std::string lowercase(const std::string& text) {
  std::string t;
  for (char c : text) t += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return t;
}

inline bool parse(const std::string& text, bool& v) {
  const std::string t = lowercase(text);
  if (t == "true" || t == "1" || t == "yes" || t == "on") return v = true, true;
  if (t == "false" || t == "0" || t == "no" || t == "off") return v = false, true;
  return false;
}

inline bool parse(const std::string& text, unsigned& v) {
  std::uint64_t x = 0;
  if (!parse(text, x) || x > std::numeric_limits<unsigned>::max()) return false;
  v = static_cast<unsigned>(x);
  return true;
}

inline bool parse(const std::string& text, MayBeInfinite<double> w) {
  const std::string t = lowercase(text);
  if (t == "inf" || t == "+inf" || t == "infinity") return w.value = std::numeric_limits<double>::infinity(), true;
  return parse(text, w.value);
}

inline bool parse(const std::string& text, CandidateKey& v) {
  if (text == "quantiles") return v = CandidateKey::kQuantiles, true;
  if (text == "mean") return v = CandidateKey::kMean, true;
  return false;
}

inline bool parse(const std::string& text, RobustLoss& v) {
  if (text == "none") return v = RobustLoss::kNone, true;
  if (text == "huber") return v = RobustLoss::kHuber, true;
  if (text == "cauchy") return v = RobustLoss::kCauchy, true;
  return false;
}

inline bool parse(const std::string& text, PoseSolver& v) {
  if (text == "ceres") return v = PoseSolver::kCeres, true;
  if (text == "normal_equations") return v = PoseSolver::kNormalEquations, true;
  return false;
}

inline bool parse(const std::string& text, LoopSearch& v) {
  if (text == "radius") return v = LoopSearch::kRadius, true;
  if (text == "retrieval") return v = LoopSearch::kRetrieval, true;
  if (text == "both") return v = LoopSearch::kBoth, true;
  return false;
}

/// A comma-separated list of finite numbers (at least one).
inline bool parse(const std::string& text, std::vector<double>& v) {
  std::vector<double> out;
  std::size_t b = 0;
  while (true) {
    const std::size_t e = text.find(',', b);
    double x = 0;
    if (!parse(trimmed(text.substr(b, e == std::string::npos ? std::string::npos : e - b)), x)) return false;
    out.push_back(x);
    if (e == std::string::npos) break;
    b = e + 1;
  }
  v = std::move(out);
  return true;
}

inline const char* typeName(const double&) { return "a finite number"; }
inline const char* typeName(const int&) { return "an integer"; }
inline const char* typeName(const unsigned&) { return "a non-negative integer"; }
inline const char* typeName(const std::uint64_t&) { return "a non-negative integer"; }
inline const char* typeName(const bool&) { return "true or false"; }
template <class D>
inline const char* typeName(const MayBeInfinite<D>&) { return "a number or inf"; }
inline const char* typeName(const CandidateKey&) { return "quantiles or mean"; }
inline const char* typeName(const RobustLoss&) { return "none, huber or cauchy"; }
inline const char* typeName(const PoseSolver&) { return "ceres or normal_equations"; }
inline const char* typeName(const LoopSearch&) { return "radius, retrieval or both"; }
inline const char* typeName(const std::vector<double>&) { return "a comma-separated list of finite numbers"; }

inline std::string toText(double v) { return mrpt::format("%.17g", v); }  // exact: reads back to the same double
inline std::string toText(int v) { return std::to_string(v); }
inline std::string toText(unsigned v) { return std::to_string(v); }
inline std::string toText(std::uint64_t v) { return std::to_string(v); }
inline std::string toText(bool v) { return v ? "true" : "false"; }
template <class D>
inline std::string toText(const MayBeInfinite<D>& w) { return std::isinf(w.value) ? "inf" : toText(static_cast<double>(w.value)); }
inline std::string toText(CandidateKey v) { return v == CandidateKey::kMean ? "mean" : "quantiles"; }
inline std::string toText(RobustLoss v) {
  return v == RobustLoss::kNone ? "none" : v == RobustLoss::kCauchy ? "cauchy" : "huber";
}
inline std::string toText(LoopSearch v) {
  return v == LoopSearch::kRetrieval ? "retrieval" : v == LoopSearch::kBoth ? "both" : "radius";
}
inline std::string toText(PoseSolver v) { return v == PoseSolver::kCeres ? "ceres" : "normal_equations"; }
inline std::string toText(const std::vector<double>& v) {
  std::string s;
  for (const double x : v) s += (s.empty() ? "" : ",") + toText(x);
  return s;
}

template <class T>
void readOne(const mrpt::config::CConfigFileBase& source, const std::string& section, const std::string& key, T&& field) {
  if (!source.keyExists(section, key)) return;
  const std::string text = trimmed(source.read_string(section, key, ""));
  if (!parse(text, field)) {
    THROW_EXCEPTION_FMT("[%s] %s = '%s': expected %s", section.c_str(), key.c_str(), text.c_str(), typeName(field));
  }
}

/// One YAML value: plain numbers and flags as MRPT's YAML converts them; names, "inf" and lists
/// through the strict text parsing above (a list as a YAML sequence or as "a,b,c").
template <class T>
bool fromYaml(const mrpt::containers::yaml& node, T&& field) {
  using V = std::decay_t<T>;
  try {
    if constexpr (std::is_same_v<V, double> || std::is_same_v<V, int> || std::is_same_v<V, bool> ||
                  std::is_same_v<V, unsigned> || std::is_same_v<V, std::uint64_t>) {
      field = node.template as<V>();
      return true;
    } else if constexpr (std::is_same_v<V, std::vector<double>>) {
      if (!node.isSequence()) return parse(trimmed(node.template as<std::string>()), field);
      std::vector<double> v;
      for (const auto& e : node.asSequence()) v.push_back(e.template as<double>());
      if (v.empty() || !std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); })) return false;
      field = std::move(v);
      return true;
    } else {
      return parse(trimmed(node.template as<std::string>()), std::forward<T>(field));
    }
  } catch (const std::exception&) {
    return false;
  }
}

}  // namespace gasp::detail
