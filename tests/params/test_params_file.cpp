// gasp/params/params_file.h: every parameter in one YAML file, section by section; what is written
// reads back to the same values; the shipped defaults file loads to the defaults; docs/parameters.md
// lists every key with its default; bad files are errors naming the file, the line and the key.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <string>

#include "gasp/core/error.h"
#include "gasp/params/params_file.h"
#include "gasp_test_data.h"

namespace {

std::string readError(const std::string& yaml) {
  try {
    gasp::readParamsYaml(yaml, "params 'test.yaml'");
  } catch (const gasp::Error& e) {
    return e.what();
  }
  return "";
}

/// section -> key -> value text, as paramsYaml writes them.
std::map<std::string, std::map<std::string, std::string>> valuesOf(const std::string& yaml) {
  std::map<std::string, std::map<std::string, std::string>> out;
  std::istringstream in(yaml);
  std::string line, section;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    const auto colon = line.find(':');
    if (line[0] != ' ') {
      section = line.substr(0, colon);
      continue;
    }
    out[section][line.substr(2, colon - 2)] = line.substr(colon + 2);
  }
  return out;
}

}  // namespace

TEST(ParamsFile, EverySectionHasKeysAndEveryKeyIsWritten) {
  const auto values = valuesOf(gasp::paramsYaml(gasp::SlamParams{}));
  std::size_t keys = 0;
  for (const auto& section : gasp::paramsSections()) {
    ASSERT_FALSE(gasp::paramsKeys(section).empty()) << section;
    ASSERT_EQ(values.at(section).size(), gasp::paramsKeys(section).size()) << section;
    keys += values.at(section).size();
  }
  EXPECT_GT(keys, 130u);  // the pair pipeline's 115 and more, the odometry's, the loop closer's, the graph's
  EXPECT_TRUE(gasp::paramsKeys("no_such_section").empty());
}

TEST(ParamsFile, WhatIsWrittenReadsBackToTheSameValues) {
  const gasp::SlamParams defaults;
  EXPECT_TRUE(gasp::sameParams(gasp::readParamsYaml(gasp::paramsYaml(defaults), "defaults"), defaults));
  // One value changed in each section, of every kind: number, integer, count, flag, name, inf, list.
  gasp::SlamParams p;
  auto& pair = p.odometry.pair;
  pair.segment.target_patch_area_m2 = 0.0031;
  pair.segment.borders.step_borders = true;
  pair.associate.lambda = 0.1 + 0.2;  // not a short decimal
  pair.associate.costs.transpose = std::numeric_limits<double>::infinity();
  pair.associate.candidate_key = gasp::CandidateKey::kMean;
  pair.hypothesise.pose.ransac.seed = 4000000000u;
  pair.hypothesise.pose.refinement.loss = gasp::RobustLoss::kCauchy;
  pair.refine.dense.gates_m = {0.2, 0.07, 0.03, 0.01};
  pair.refine.dense.rounds = 4;
  pair.certify.visibility.max_occluded_ratio = 0.45;
  pair.retry.finer_area_factor = 0.25;
  p.odometry.keyframe_angle_deg = 7.5;
  p.odometry.scene_change.enabled = false;
  p.loop.min_keyframe_gap = 9;
  p.loop.gate_chi2 = 16.81;
  p.graph.function_tolerance = 1e-12;
  p.lidar.patch_area_m2 = 0.7;
  p.lidar.returns_look_up_columns = 3;
  p.lidar.dense_sample_spacing_deg = 1.25;
  p.lidar.ground_search = false;
  p.lidar.ground_search_max_offset_m = 12.5;
  ASSERT_FALSE(gasp::sameParams(p, defaults));
  const gasp::SlamParams back = gasp::readParamsYaml(gasp::paramsYaml(p), "changed");
  EXPECT_TRUE(gasp::sameParams(back, p)) << gasp::paramsYaml(back);
  EXPECT_EQ(back.odometry.pair.associate.lambda, 0.1 + 0.2);
  EXPECT_EQ(back.odometry.pair.refine.dense.gates_m, p.odometry.pair.refine.dense.gates_m);
  EXPECT_EQ(back.loop.min_keyframe_gap, 9u);
  EXPECT_EQ(back.lidar.patch_area_m2, 0.7);
  EXPECT_EQ(back.lidar.returns_look_up_columns, 3);
  EXPECT_EQ(back.lidar.dense_sample_spacing_deg, 1.25);
  EXPECT_FALSE(back.lidar.ground_search);
  EXPECT_EQ(back.lidar.ground_search_max_offset_m, 12.5);
  EXPECT_TRUE(std::isinf(back.odometry.pair.associate.costs.transpose));
  // A file sets only what it names; the rest keeps the values it is read over.
  const gasp::SlamParams partial = gasp::readParamsYaml("associate:\n  candidates: 7\n", "partial", p);
  EXPECT_EQ(partial.odometry.pair.associate.candidates, 7);
  EXPECT_EQ(partial.loop.gate_chi2, 16.81);
}

TEST(ParamsFile, TheYamlFormsOfAValueAllRead) {
  const std::string yaml =
      "%YAML 1.2\n"
      "---\n"
      "# a comment line\n"
      "refine:   # a section's comment\n"
      "  dense_gates_m:\n"
      "    - 0.1\n"
      "    - 0.02\n"
      "  dense_loss: 'cauchy'\n"
      "  edge_terms: \"false\"\n"
      "associate:\n"
      "  cost_replace: inf\n"
      "  lambda: 0.5  # trailing comment\n"
      "pose_graph: {}\n"
      "...\n";
  const gasp::SlamParams p = gasp::readParamsYaml(yaml, "forms");
  EXPECT_EQ(p.odometry.pair.refine.dense.gates_m, (std::vector<double>{0.1, 0.02}));
  EXPECT_EQ(p.odometry.pair.refine.solver.loss, gasp::RobustLoss::kCauchy);
  EXPECT_FALSE(p.odometry.pair.refine.edges.enabled);
  EXPECT_EQ(p.odometry.pair.associate.lambda, 0.5);
  EXPECT_TRUE(gasp::sameParams(gasp::readParamsYaml("", "empty"), gasp::SlamParams{}));
}

TEST(ParamsFile, BadFilesAreErrorsNamingTheLineAndTheKey) {
  const struct {
    const char* yaml;
    const char* expected;
  } cases[] = {
      {"assoziate:\n  lambda: 0.5\n", "params 'test.yaml' line 1: unknown section 'assoziate' (sections: segment, associate,"},
      {"associate:\n  lamda: 0.5\n", "params 'test.yaml' line 2: unknown key 'lamda' in section 'associate' (its keys: neighbourhood_k,"},
      {"associate:\n  lambda: abc\n", "params 'test.yaml' line 2: associate.lambda = 'abc': expected a finite number"},
      {"associate:\n  candidates: 2.5\n", "line 2: associate.candidates = '2.5': expected an integer"},
      {"associate:\n  mutual_check: maybe\n", "line 2: associate.mutual_check = 'maybe': expected true or false"},
      {"associate:\n  candidate_key: median\n", "line 2: associate.candidate_key = 'median': expected quantiles or mean"},
      {"associate:\n  lambda: [0.5, 0.6]\n", "line 2: associate.lambda = '[0.5,0.6]': expected a finite number"},
      {"loop_closure:\n  min_keyframe_gap: -1\n", "line 2: loop_closure.min_keyframe_gap = '-1': expected a non-negative integer"},
      {"refine:\n  dense_gates_m: [0.1, 0.05\n", "line 2: a list without its closing ']'"},
      {"associate:\n  lambda: 0.5\n  lambda: 0.6\n", "line 3: key 'associate.lambda' a second time"},
      {"associate:\n  lambda: 0.5\nassociate:\n  candidates: 3\n", "line 3: section 'associate' a second time"},
      {"lambda: 0.5\n", "line 1: section 'lambda' holds keys on the lines below it, not a value ('0.5')"},
      {"  lambda: 0.5\n", "line 1: key 'lambda' before any section"},
      {"associate:\n\tlambda: 0.5\n", "line 2: a tab in the indentation"},
      {"associate:\n  lambda 0.5\n", "line 2: 'lambda 0.5' is not 'key: value'"},
      {"associate:\n  lambda:\n", "line 2: no value for this key"},
      {"associate:\n  lambda:\n  candidates: 3\n", "line 3: no value for the key above"},
      {"associate:\n  lambda: \"0.5\n", "line 2: a quoted value without its closing quote"},
      {"associate:\n  lambda: {a: 1}\n", "line 2: '{a: 1}' is not a plain value"},
      {"associate:\n  lambda: 0.5\n---\n", "line 3: '---' after the first section"},
      // Valid alone but not together with the defaults: the key and its line are named.
      {"associate:\n  lambda: 1.5\n", "params 'test.yaml': invalid parameters (associate.lambda on line 2):"},
      {"refine:\n  dense_rounds: 3\n  dense_gates_m: [0.1, -0.05]\n",
       "params 'test.yaml': invalid parameters (refine.dense_gates_m on line 3): dense rounds: gates must be finite and positive"},
  };
  for (const auto& c : cases) {
    const std::string error = readError(c.yaml);
    EXPECT_NE(error.find(c.expected), std::string::npos) << c.yaml << "\n-> " << error;
  }
  try {
    gasp::readParamsFile("/no/such/params.yaml");
    ADD_FAILURE() << "no error for a missing file";
  } catch (const gasp::Error& e) {
    EXPECT_STREQ(e.what(), "params '/no/such/params.yaml': cannot open the file");
  }
  // Not a params file: a device read without end, a folder, a file of megabytes.
  auto fileError = [](const std::string& path) {
    try {
      gasp::readParamsFile(path);
    } catch (const gasp::Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(fileError("/dev/zero"), "params '/dev/zero': not a regular file (a params file is a YAML text file)");
  EXPECT_EQ(fileError("/tmp"), "params '/tmp': not a regular file (a params file is a YAML text file)");
  const std::string big = gasp::test::scratchDir() + "/big.yaml";
  std::ofstream(big) << std::string(gasp::kMaxParamsFileBytes + 1, '#');
  EXPECT_NE(fileError(big).find("bytes, more than a params file holds"), std::string::npos) << fileError(big);
}

TEST(ParamsFile, WrittenThroughATemporaryFileThatLoadsBack) {
  const std::string dir = gasp::test::scratchDir();
  const std::string path = dir + "/out.yaml";
  gasp::SlamParams p;
  p.odometry.rolling_shutter_readout_s = 0.03;
  gasp::writeParamsFile(p, path);
  EXPECT_TRUE(gasp::sameParams(gasp::readParamsFile(path), p));
  std::size_t files = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir)) files += e.is_regular_file();
  EXPECT_EQ(files, 1u);  // no temporary file left
  EXPECT_THROW(gasp::writeParamsFile(p, dir + "/no_such_dir/out.yaml"), gasp::Error);
}

// The shipped file of defaults: every key, and it loads to the defaults.
TEST(ParamsFile, TheShippedDefaultsFileLoadsToTheDefaults) {
  const std::string path = std::string(GASP_SOURCE_DIR) + "/params/gasp.yaml";
  const gasp::SlamParams loaded = gasp::readParamsFile(path);
  EXPECT_TRUE(gasp::sameParams(loaded, gasp::SlamParams{}));
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  const auto shipped = valuesOf(text.str());
  for (const auto& section : gasp::paramsSections())
    for (const auto& key : gasp::paramsKeys(section))
      EXPECT_TRUE(shipped.count(section) && shipped.at(section).count(key)) << "params/gasp.yaml has no " << section << "." << key;
}

// docs/parameters.md: a "## `section`" heading per section and a table row per key whose
// default (2nd column) is the value paramsYaml writes (numbers within 1e-6, relative).
TEST(ParamsFile, DocsListEveryKeyWithItsDefault) {
  std::ifstream in(std::string(GASP_SOURCE_DIR) + "/docs/parameters.md");
  ASSERT_TRUE(in) << "docs/parameters.md not found";
  std::map<std::string, std::map<std::string, std::string>> documented;
  std::string line, section;
  while (std::getline(in, line)) {
    if (line.rfind("## `", 0) == 0) {
      section = line.substr(4, line.find('`', 4) - 4);
      continue;
    }
    if (section.empty() || line.rfind("| `", 0) != 0) continue;
    const auto key_end = line.find('`', 3);
    const std::string key = line.substr(3, key_end - 3);
    const auto cell = line.find('|', key_end) + 1;
    std::string value = line.substr(cell, line.find('|', cell) - cell);
    value.erase(0, value.find_first_not_of(' '));
    value.erase(value.find_last_not_of(' ') + 1);
    documented[section][key] = value;
  }
  auto same = [](std::string a, std::string b) {
    auto strip = [](std::string s) {
      std::string o;
      for (char c : s)
        if (c != ' ' && c != '[' && c != ']' && c != '`') o += c;
      return o;
    };
    a = strip(a);
    b = strip(b);
    if (a == b) return true;
    std::stringstream sa(a), sb(b);
    std::string xa, xb;
    while (true) {
      const bool ga = static_cast<bool>(std::getline(sa, xa, ',')), gb = static_cast<bool>(std::getline(sb, xb, ','));
      if (ga != gb) return false;
      if (!ga) return true;
      char* ea = nullptr;
      char* eb = nullptr;
      const double va = std::strtod(xa.c_str(), &ea), vb = std::strtod(xb.c_str(), &eb);
      if (*ea || *eb || ea == xa.c_str() || eb == xb.c_str()) return false;
      if (!(std::abs(va - vb) <= 1e-6 * std::max(std::abs(va), std::abs(vb)))) return false;
    }
  };
  const auto values = valuesOf(gasp::paramsYaml(gasp::SlamParams{}));
  for (const auto& [s, keys] : values)
    for (const auto& [key, value] : keys) {
      if (!documented.count(s) || !documented.at(s).count(key)) {
        ADD_FAILURE() << "docs/parameters.md has no row for " << s << "." << key;
        continue;
      }
      EXPECT_TRUE(same(documented.at(s).at(key), value))
          << s << "." << key << ": documented " << documented.at(s).at(key) << ", default " << value;
    }
  for (const auto& [s, keys] : documented)
    for (const auto& [key, value] : keys)
      EXPECT_TRUE(values.count(s) && values.at(s).count(key)) << "docs/parameters.md documents " << s << "." << key << ", which is no key";
}
