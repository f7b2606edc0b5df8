// gasp/params/params_io.h: every parameter of SuperpixelParams and PairParams is an ini / YAML key
// that reads back exactly what was written (so maps serialised through their option text keep all
// of them), and the special kinds of value (names, inf, lists) parse strictly. (docs/parameters.md
// lists every key with its default: tests/params.)
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/containers/yaml.h>
#include <mrpt/io/CMemoryStream.h>
#include <mrpt/serialization/CArchive.h>

#include <cmath>
#include <algorithm>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <regex>
#include <sstream>
#include <string>

#include "gasp/mrpt/CSuperpixelMap.h"
#include "gasp/mrpt/ObservationMatcher_GASP.h"
#include "gasp/mrpt/observation_matcher.h"
#include "gasp/params/params_file.h"
#include "gasp_test_data.h"
#include "gasp/params/params_io.h"

using namespace gasp;

namespace {

/// Key -> text of an ini section written by `write`.
template <class Write>
std::map<std::string, std::string> keysOf(Write write) {
  mrpt::config::CConfigFileMemory mem;
  write(mem);
  std::vector<std::string> keys;
  mem.getAllKeys("s", keys);
  std::map<std::string, std::string> out;
  for (const auto& k : keys) out[k] = mem.read_string("s", k, "");
  return out;
}

std::map<std::string, std::string> pairKeys(const PairParams& p) {
  return keysOf([&](auto& mem) { writePairParams(p, mem, "s"); });
}

/// Every field of PairParams away from its default (and still valid).
PairParams everythingChanged() {
  PairParams p;
  auto& s = p.segment;
  s.surfaces.discontinuity_abs_m = 0.0123456789, s.surfaces.discontinuity_rel = 0.021, s.surfaces.normal_window_px_per_m = 6.5;
  s.surfaces.normal_min_radius_px = 3, s.surfaces.normal_max_radius_px = 11, s.surfaces.max_crease_angle_deg = 26;
  s.surfaces.max_neighbour_normal_angle_deg = 11, s.surfaces.min_component_pixels = 41, s.target_patch_area_m2 = 0.0051;
  s.kmeans.kmeans_iterations = 7, s.kmeans.kmeans_normal_weight = 0.55, s.kmeans.seed_sampling_step_px = 3, s.kmeans.seed = 99;
  s.max_incidence_deg = 79, s.cleanup.min_patch_pixels = 21, s.cleanup.min_patch_area_ratio = 0.26;
  s.cleanup.regrow_normal_weight_m = 0.11, s.processing_step_px = 1, s.kmeans.kmeans_iteration_step_px = 1;
  s.kmeans.kmeans_coarse_iterations = 3, s.borders.crease_borders = false, s.borders.crease_min_angle_deg = 31, s.borders.crease_band_px = 9;
  s.borders.plane_noise_abs_m = 0.0051, s.borders.plane_noise_rel = 0.0031, s.borders.step_borders = true, s.borders.step_min_sigmas = 6.5;
  s.borders.step_smoothness = 1.5;
  p.certify.view_degeneracy.min_eigenvalue_ratio = 2e-3;
  auto& a = p.associate;
  a.feature_sets.neighbourhood.k = 25, a.feature_sets.feature.e_theta_rad = 0.09;
  a.feature_sets.feature.min_separation_m = 2e-6, a.feature_sets.ordering.e_r_m = 0.025;
  a.feature_sets.ordering.e_theta_rad = 0.1, a.match.r_dev_m = 0.045, a.match.theta_dev_rad = 0.2;
  a.costs.insert = 1.5, a.costs.del = 1.25, a.costs.replace = 2.0;
  a.costs.transpose = std::numeric_limits<double>::infinity();
  a.candidates = 21, a.lambda = 0.65, a.mutual_check = false, a.candidate_key = CandidateKey::kMean;
  a.distinctiveness_ratio = 0.9;
  auto& r = p.hypothesise.pose.ransac;
  r.inlier.distance_m = 0.06, r.inlier.normal_angle_deg = 21, r.edge_tolerance_m = 0.031;
  r.normal_pair_tolerance_deg = 19, r.min_triangle_height_m = 0.051, r.min_inliers = 9, r.max_iterations = 9000;
  r.confidence = 0.99, r.seed = 7, r.guided_sampling = false, r.min_iterations = 150;
  r.max_guided_correspondences = 1400;
  auto& q = p.hypothesise.pose.refinement;
  q.loss = RobustLoss::kCauchy, q.loss_scale_m = 0.03, q.bidirectional = false, q.max_iterations = 40;
  q.solver = PoseSolver::kCeres;
  q.noise_sigma_m = 0.012, q.degeneracy.min_eigenvalue_ratio = 2e-3, q.degeneracy.max_std_m = 0.06;
  p.retry.one_way_fallback = false, p.certify.fallback_max_violation_ratio = 0.09, p.hypothesise.guided.enabled = false;
  p.hypothesise.guided.densify = true, p.hypothesise.guided.gates.max_distance_m = 0.04, p.hypothesise.guided.gates.max_normal_angle_deg = 21;
  p.hypothesise.guided.gates.lambda = 0.75, p.hypothesise.guided.min_support = 13, p.hypothesise.pose.refine = false, p.refine.dense.rounds = 2;
  p.refine.dense.gates_m = {0.2, 0.04};
  p.refine.dense.max_rounds = 12, p.refine.dense.converged_m = 0.003, p.refine.dense.extrapolation_max = 3;
  p.refine.dense.line_search = false, p.refine.dense.line_search_halvings = 2;
  p.refine.pixels.pixel_step = 6, p.refine.pixels.max_distance_m = 0.06, p.refine.pixels.max_normal_angle_deg = 22;
  p.refine.edges.enabled = false, p.refine.edges.terms.min_jump_m = 0.06, p.refine.edges.terms.jump_per_m2 = 0.03, p.refine.edges.terms.pixel_step = 10;
  p.refine.edges.terms.line_neighbours = 6, p.refine.edges.terms.max_distance_m = 0.07, p.refine.edges.terms.weight = 1.5;
  p.refine.edges.wide_gate_factor = 2.5, p.refine.edges.wide_min_paired_share = 0.5;
  p.refine.solver.degeneracy.min_eigenvalue_ratio = 2e-3, p.refine.solver.degeneracy.max_std_m = 0.06, p.certify.min_dense_terms = 250;
  p.certify.partial_poses = false;
  p.refine.slide_scan.enabled = false, p.refine.slide_scan.range_m = 0.25, p.refine.slide_scan.step_m = 0.02;
  p.refine.slide_scan.min_gain = 0.006, p.refine.slide_scan.pixel_step = 6;
  p.certify.visibility.pixel_step = 6, p.certify.visibility.gate_m = 0.035, p.certify.visibility.gate_per_m2 = 0.025;
  p.certify.visibility.max_violation_ratio = 0.2, p.certify.visibility.max_occluded_ratio = 0.6, p.certify.visibility.min_consistent = 40;
  p.certify.visibility.max_two_way_violation_ratio = 0.07;
  p.certify.visibility.pixel_spread = true, p.refine.pixels.pixel_footprint = true;
  p.refine.pixels.sample_spacing_deg = 0.5;
  p.hypothesise.pose.reselection_rounds = 3;
  auto& d = p.refine.solver;
  d.loss = RobustLoss::kCauchy, d.loss_scale_m = 0.025, d.bidirectional = false, d.max_iterations = 45;
  d.solver = PoseSolver::kCeres;
  d.noise_sigma_m = 0.011;
  p.retry.finer_area_factor = 0.4, p.certify.model_error.sigma_t_m = 0.02, p.certify.model_error.sigma_r_deg = 1.0;
  p.certify.min_likelihood_ratio = 500;
  p.certify.symmetry_test = true;
  p.certify.violation_nats = 1.25;
  return p;
}

}  // namespace

TEST(ParamsIo, EveryPairParameterIsAKeyThatReadsBackExactly) {
  const PairParams changed = everythingChanged();
  ASSERT_NO_THROW(validate(changed));
  const auto defaults = pairKeys(PairParams{});
  const auto written = pairKeys(changed);
  ASSERT_EQ(written.size(), defaults.size());
  // Every key was changed by everythingChanged(), so each one below is a real round trip.
  for (const auto& [key, text] : written) EXPECT_NE(text, defaults.at(key)) << key << " kept its default";
  mrpt::config::CConfigFileMemory mem;
  writePairParams(changed, mem, "s");
  PairParams read;
  readPairParams(mem, "s", read);
  EXPECT_EQ(pairKeys(read), written);
  // The kinds of value with their own syntax, field by field.
  EXPECT_EQ(read.segment.surfaces.discontinuity_abs_m, 0.0123456789);  // exactly: %.17g
  EXPECT_EQ(read.associate.candidate_key, CandidateKey::kMean);
  EXPECT_TRUE(std::isinf(read.associate.costs.transpose));
  EXPECT_EQ(read.associate.costs.replace, 2.0);
  EXPECT_EQ(read.hypothesise.pose.refinement.loss, RobustLoss::kCauchy);
  EXPECT_EQ(read.refine.solver.solver, PoseSolver::kCeres);
  EXPECT_EQ(read.refine.dense.gates_m, (std::vector<double>{0.2, 0.04}));
  EXPECT_EQ(read.hypothesise.pose.ransac.seed, 7u);
  EXPECT_EQ(written.at("cost_replace"), "2");
  EXPECT_EQ(defaults.at("cost_replace"), "inf");
  EXPECT_EQ(defaults.at("dense_gates_m"), "0.10000000000000001,0.050000000000000003,0.029999999999999999");
  // Every segmentation key is a pair key too (the matcher segments its observations with them).
  const auto seg = keysOf([&](auto& m) { writeSuperpixelParams(changed.segment, m, "s"); });
  EXPECT_EQ(seg.size(), 28u);
  for (const auto& [key, text] : seg) EXPECT_EQ(written.at(key), text) << key;
}

TEST(ParamsIo, SpecialValuesParseStrictlyInIniAndYaml) {
  auto readIni = [](const std::string& body) {
    PairParams p;
    readPairParams(mrpt::config::CConfigFileMemory("[s]\n" + body), "s", p);
    return p;
  };
  EXPECT_EQ(readIni("dense_gates_m = 0.2, 0.1 ,0.05\n").refine.dense.gates_m, (std::vector<double>{0.2, 0.1, 0.05}));
  EXPECT_TRUE(std::isinf(readIni("cost_transpose=Infinity\n").associate.costs.transpose));
  EXPECT_EQ(readIni("refinement_loss=none\n").hypothesise.pose.refinement.loss, RobustLoss::kNone);
  EXPECT_EQ(readIni("dense_solver=ceres\n").refine.solver.solver, PoseSolver::kCeres);
  for (const char* bad : {"dense_gates_m=0.1,,0.05\n", "dense_gates_m=\n", "candidate_key=median\n",
                          "refinement_loss=Huber\n", "dense_solver=lm\n", "cost_insert=inf\n", "cost_replace=-inf\n", "cost_replace=nan\n",
                          "ransac_seed=-1\n", "ransac_seed=99999999999\n"}) {
    try {
      readIni(bad);
      ADD_FAILURE() << "accepted: " << bad;
    } catch (const std::exception& e) {
      const std::string key = std::string(bad).substr(0, std::string(bad).find('='));
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
    }
  }
  PairParams y;
  readPairParams(mrpt::containers::yaml::FromText("candidate_key: mean\ndense_gates_m: [0.2, 0.1]\n"
                                                  "cost_replace: inf\nrefinement_loss: cauchy\nransac_seed: 5\n"),
                 "matcher", y);
  EXPECT_EQ(y.associate.candidate_key, CandidateKey::kMean);
  EXPECT_EQ(y.refine.dense.gates_m, (std::vector<double>{0.2, 0.1}));
  EXPECT_TRUE(std::isinf(y.associate.costs.replace));
  EXPECT_EQ(y.hypothesise.pose.refinement.loss, RobustLoss::kCauchy);
  EXPECT_EQ(y.hypothesise.pose.ransac.seed, 5u);
  PairParams z;
  EXPECT_THROW(readPairParams(mrpt::containers::yaml::FromText("dense_gates_m: [0.2, abc]\n"), "matcher", z),
               std::exception);
  EXPECT_THROW(readPairParams(mrpt::containers::yaml::FromText("candidate_key: 3\n"), "matcher", z), std::exception);
}

TEST(ParamsIo, AMapKeepsItsOptionsAndEachViewItsOwnSegmentationThroughSerialization) {
  // A flat wall with a box in front: enough patches for a view.
  RgbdFrame f;
  f.depth_intrinsics = CameraIntrinsics::tumFreiburg3();
  f.depth_m = cv::Mat(480, 640, CV_32FC1, cv::Scalar(2.0f));
  f.depth_m(cv::Rect(200, 150, 200, 150)).setTo(1.5f);
  CSuperpixelMap map;
  map.creationOptions.superpixels = everythingChanged().segment;
  map.creationOptions.superpixels.processing_step_px = 2;  // keep the test quick
  map.insertFrame(f);
  const SuperpixelParams first = map.creationOptions.superpixels;
  map.creationOptions.superpixels.target_patch_area_m2 = 0.008;  // the next view is made otherwise
  map.insertFrame(f);
  map.likelihoodOptions.matching = everythingChanged();
  map.likelihoodOptions.sigma_m = 0.0123456;  // MRPT's write(double) would keep 6 decimals
  mrpt::io::CMemoryStream buf;
  mrpt::serialization::archiveFrom(buf) << map;
  buf.Seek(0);
  CSuperpixelMap back;
  mrpt::serialization::archiveFrom(buf) >> back;
  auto text = [](const mrpt::config::CLoadableOptions& o) {
    mrpt::config::CConfigFileMemory mem;
    o.saveToConfigFile(mem, "s");
    return mem.getContent();
  };
  EXPECT_EQ(text(back.creationOptions), text(map.creationOptions));
  EXPECT_EQ(text(back.likelihoodOptions), text(map.likelihoodOptions));
  EXPECT_EQ(back.likelihoodOptions.sigma_m, 0.0123456);
  ASSERT_EQ(back.views().size(), 2u);
  auto seg = [](const SuperpixelParams& p) {
    return keysOf([&](auto& m) { writeSuperpixelParams(p, m, "s"); });
  };
  EXPECT_EQ(seg(back.views()[0].view.superpixels), seg(first));
  EXPECT_EQ(back.views()[1].view.superpixels.target_patch_area_m2, 0.008);
}

TEST(ParamsIo, VersionZeroMapsStillLoadAndUnknownVersionsAreRefused) {
  // Without views the four versions have the same layout; only the version byte after the class
  // name differs (MRPT's object format: class name, version, data, end marker).
  CSuperpixelMap map;
  map.creationOptions.superpixels.target_patch_area_m2 = 0.006;
  mrpt::io::CMemoryStream buf;
  mrpt::serialization::archiveFrom(buf) << map;
  const auto* p = static_cast<const std::uint8_t*>(buf.getRawBufferData());
  std::vector<std::uint8_t> bytes(p, p + buf.getTotalBytesCount());
  const std::string name = "gasp::CSuperpixelMap";
  const auto at = std::search(bytes.begin(), bytes.end(), name.begin(), name.end());
  ASSERT_NE(at, bytes.end());
  const std::size_t version_byte = static_cast<std::size_t>(at - bytes.begin()) + name.size();
  ASSERT_EQ(bytes[version_byte], 3);
  auto load = [&](std::uint8_t version) {
    bytes[version_byte] = version;
    mrpt::io::CMemoryStream in;
    in.assignMemoryNotOwn(bytes.data(), bytes.size());
    CSuperpixelMap back;
    mrpt::serialization::archiveFrom(in) >> back;
    return back;
  };
  EXPECT_EQ(load(0).creationOptions.superpixels.target_patch_area_m2, 0.006);
  EXPECT_EQ(load(1).creationOptions.superpixels.target_patch_area_m2, 0.006);
  EXPECT_EQ(load(2).creationOptions.superpixels.target_patch_area_m2, 0.006);
  EXPECT_THROW(load(4), std::exception);
}

// The params file every program loads (gasp/params/params_file.h) is also what the MRPT classes
// take: the matcher created by name in its YAML form (`params_file:` and sections), the aligner,
// a map and the graphslam deciders through a `params_file` key in their ini section, each with
// its own keys over the file's.
TEST(ParamsIo, TheMrptClassesTakeTheParamsFile) {
  const std::string dir = gasp::test::scratchDir();
  const std::string file = dir + "/params.yaml";
  std::ofstream(file) << "associate:\n  lambda: 0.6\n  candidate_key: mean\nrefine:\n  dense_gates_m: [0.12, 0.04]\n"
                         "segment:\n  target_patch_area_m2: 0.005\nodometry:\n  keyframe_angle_deg: 7\n";
  const gasp::SlamParams expected = gasp::readParamsFile(file);
  // The matcher, by name: the file, then a section over it.
  const auto matcher = gasp::createObservationMatcher(
      "gasp::ObservationMatcher_GASP",
      mrpt::containers::yaml::FromText("params_file: " + file + "\nassociate:\n  candidates: 9\n"));
  const auto* gasp_matcher = dynamic_cast<const gasp::ObservationMatcher_GASP*>(matcher.get());
  ASSERT_NE(gasp_matcher, nullptr);
  gasp::SlamParams got = expected;
  got.odometry.pair = gasp_matcher->params;
  EXPECT_EQ(got.odometry.pair.associate.candidates, 9);
  got.odometry.pair.associate.candidates = expected.odometry.pair.associate.candidates;
  EXPECT_TRUE(gasp::sameParams(got, expected));
  // The whole file's text as the matcher's YAML: the same values.
  std::ifstream in(file);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  PairParams from_text;
  readPairParams(mrpt::containers::yaml::FromText(text), "matcher", from_text);
  got.odometry.pair = from_text;
  EXPECT_TRUE(gasp::sameParams(got, expected));
  // Flat keys and sections do not mix; a bad file is named.
  PairParams z;
  EXPECT_THROW(readPairParams(mrpt::containers::yaml::FromText("lambda: 0.5\nassociate:\n  candidates: 3\n"), "m", z),
               std::exception);
  try {
    readPairParams(mrpt::containers::yaml::FromText("params_file: " + dir + "/none.yaml\n"), "matcher", z);
    ADD_FAILURE() << "no error for a missing params file";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("matcher: params '" + dir + "/none.yaml': cannot open the file"), std::string::npos)
        << e.what();
  }
  // An ini section (CGaspAligner's options, a decider's section): params_file, then its own keys.
  mrpt::config::CConfigFileMemory ini;
  ini.write("Aligner", "params_file", file);
  ini.write("Aligner", "min_inliers", "11");
  PairParams aligned;
  readPairParams(ini, "Aligner", aligned);
  EXPECT_EQ(aligned.hypothesise.pose.ransac.min_inliers, 11);
  EXPECT_EQ(aligned.associate.lambda, 0.6);
  EXPECT_EQ(aligned.refine.dense.gates_m, (std::vector<double>{0.12, 0.04}));
  OdometryParams odometry;
  readOdometryParams(ini, "Aligner", odometry);
  EXPECT_EQ(odometry.keyframe_angle_deg, 7.0);
  SuperpixelParams segment;
  mrpt::config::CConfigFileMemory map_ini;
  map_ini.write("Map", "params_file", file);
  readSuperpixelParams(map_ini, "Map", segment);
  EXPECT_EQ(segment.target_patch_area_m2, 0.005);
  map_ini.write("Map", "params_file", dir + "/none.yaml");
  EXPECT_THROW(readSuperpixelParams(map_ini, "Map", segment), std::exception);
  EXPECT_EQ(segment.target_patch_area_m2, 0.005);  // unchanged by the failed read
}
