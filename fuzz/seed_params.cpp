// fuzz_seed_params (not a fuzz target; fuzz/make_seeds.sh calls it):
//   fuzz_seed_params DST_DIR
// Ini files with every key of the sections fuzz_params reads, at their defaults.
#include <mrpt/config/CConfigFileMemory.h>

#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>

#include "gasp/core/error.h"
#include "gasp/mrpt/CGaspAligner.h"
#include "gasp/mrpt/CSuperpixelMap.h"
#include "gasp/params/params_io.h"

namespace fs = std::filesystem;

namespace {

void writeText(const std::string& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
  if (!out) throw gasp::Error("cannot write " + path);
}

void paramsIni(const std::string& dst) {
  fs::create_directories(dst);
  {  // the plugin's sections, as fuzz_params names them
    mrpt::config::CConfigFileMemory mem;
    gasp::CSuperpixelMap::TCreationOptions().saveToConfigFile(mem, "M_superpixelMap_00_creationOpts");
    gasp::CSuperpixelMap::TLikelihoodOptions().saveToConfigFile(mem, "M_superpixelMap_00_likelihoodOpts");
    gasp::CSuperpixelMap::TRenderOptions().saveToConfigFile(mem, "M_superpixelMap_00_renderOpts");
    writeText(dst + "/plugin_map_defaults.ini", mem.getContent());
  }
  {
    mrpt::config::CConfigFileMemory mem;
    gasp::CGaspAligner::TOptions().saveToConfigFile(mem, "GaspAligner");
    writeText(dst + "/plugin_aligner_defaults.ini", mem.getContent());
  }
  {  // the graph-SLAM deciders read the pair keys in their sections too
    mrpt::config::CConfigFileMemory mem;
    gasp::writePairParams(gasp::PairParams{}, mem, "CGaspOdometryNRD");
    mem.write("CGaspOdometryNRD", "keyframe_distance_m", "0.2");
    mem.write("CGaspOdometryNRD", "scene_change", "1");
    mem.write("CGaspOdometryNRD", "scene_change_gate_m", "0.03");
    mem.write("CGaspOdometryNRD", "class_verbosity", "2");
    mem.write("CGaspLoopClosureERD", "search_radius_m", "0.8");
    mem.write("CGaspLoopClosureERD", "max_candidates", "4");
    mem.write("CGaspLoopClosureERD", "enabled", "1");
    mem.write("CGaspPoseGraphGSO", "max_iterations", "7");
    mem.write("CGaspPoseGraphGSO", "drop_chi2", "0");
    writeText(dst + "/graphslam_pair_keys.ini", mem.getContent());
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: fuzz_seed_params DST_DIR\n";
    return 2;
  }
  try {
    paramsIni(argv[1]);
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
