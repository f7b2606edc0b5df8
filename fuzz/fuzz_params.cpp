// fuzz_params: the bytes as an ini file, read by every GASP params/ini reader:
//  - the MRPT plugin (libgasp_mrpt): mrpt::config::CConfigFileMemory over the bytes, then the
//    loadFromConfigFile of gasp::CSuperpixelMap's creation, likelihood and render options (the
//    sections a CMultiMetricMap definition gives them, [M_superpixelMap_00_creationOpts] ...) and
//    of gasp::CGaspAligner's options ([GaspAligner]: every PairParams key, readPairParams);
//  - gasp-graphslam's configuration (libgasp_graphslam): the bytes as an ini file, checked with
//    gasp::graphslam::checkGraphSlamIni and loaded by the loadParams of CGaspOdometryNRD,
//    CGaspLoopClosureERD and CGaspPoseGraphGSO (sections named after them).
//  - the params file every program loads (libgasp_params): the bytes as its YAML text
//    (gasp::readParamsYaml); an ini section's `params_file` key names a file read the same way.
// MRPT's own multi-map loader (TSetOfMetricMapInitializers: `pointsMap_count=-1` allocates
// without end, docs/mrpt.md) is MRPT's, not GASP's, and is not fuzzed. Seeds: fuzz/make_seeds.sh
// (every key with its default, the docs' examples, gasp-graphslam.ini).
#include <mrpt/config/CConfigFileMemory.h>

#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_support.h"
#include "gasp/graphslam/CGaspLoopClosureERD.h"
#include "gasp/graphslam/CGaspOdometryNRD.h"
#include "gasp/graphslam/CGaspPoseGraphGSO.h"
#include "gasp/graphslam/ini_check.h"
#include "gasp/mrpt/CGaspAligner.h"
#include "gasp/mrpt/CSuperpixelMap.h"
#include "gasp/params/params_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const gasp::fuzz::ScratchDir dir("params");
  const std::string text(reinterpret_cast<const char*>(data), size);

  gasp::fuzz::expectErrorsOnly([&] { static_cast<void>(gasp::readParamsYaml(text, "params 'fuzz'")); });

  std::unique_ptr<mrpt::config::CConfigFileMemory> ini;
  gasp::fuzz::expectErrorsOnly([&] { ini = std::make_unique<mrpt::config::CConfigFileMemory>(text); });
  if (ini) {
    gasp::fuzz::expectErrorsOnly([&] {
      gasp::CSuperpixelMap::TCreationOptions o;
      o.loadFromConfigFile(*ini, "M_superpixelMap_00_creationOpts");
    });
    gasp::fuzz::expectErrorsOnly([&] {
      gasp::CSuperpixelMap::TLikelihoodOptions o;
      o.loadFromConfigFile(*ini, "M_superpixelMap_00_likelihoodOpts");
    });
    gasp::fuzz::expectErrorsOnly([&] {
      gasp::CSuperpixelMap::TRenderOptions o;
      o.loadFromConfigFile(*ini, "M_superpixelMap_00_renderOpts");
    });
    gasp::fuzz::expectErrorsOnly([&] {
      gasp::CGaspAligner::TOptions o;
      o.loadFromConfigFile(*ini, "GaspAligner");
    });
  }

  const std::string path = dir.write("graphslam.ini", data, size);
  gasp::fuzz::expectErrorsOnly([&] { static_cast<void>(gasp::graphslam::checkGraphSlamIni(path)); });
  gasp::fuzz::expectErrorsOnly([&] {
    gasp::graphslam::CGaspOdometryNRD nrd;
    nrd.loadParams(path);
  });
  gasp::fuzz::expectErrorsOnly([&] {
    gasp::graphslam::CGaspLoopClosureERD erd;
    erd.loadParams(path);
  });
  gasp::fuzz::expectErrorsOnly([&] {
    gasp::graphslam::CGaspPoseGraphGSO gso;
    gso.loadParams(path);
  });
  return 0;
}
