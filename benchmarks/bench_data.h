#pragma once
// Where benchmarks find the real data ($GASP_DATA_DIR, else the CMake option's default), and the
// fr1_xyz frame pairs they time.
#include <opencv2/core.hpp>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "gasp/core/tum_dataset.h"

namespace gasp::bench {

inline std::string dataDir() {
  const char* env = std::getenv("GASP_DATA_DIR");
  return (env && *env) ? env : GASP_DATA_DIR_DEFAULT;
}

struct DepthPairs {
  std::vector<std::pair<cv::Mat, cv::Mat>> depth;  ///< [m]
  CameraIntrinsics intrinsics;
};

/// n_pairs depth pairs (i, i + 10) of tum/fr1_xyz, start frames spread evenly over the sequence.
/// Throws (gasp::Error or std::runtime_error) when the data is missing or too short.
inline DepthPairs loadFr1XyzPairs(int n_pairs) {
  const auto ds = TumDataset::open(dataDir() + "/tum/fr1_xyz");
  if (ds.size() < 11 || n_pairs < 1) throw std::runtime_error("need --pairs >= 1 and at least 11 frames");
  DepthPairs p;
  p.intrinsics = ds.intrinsics();
  const std::size_t n = static_cast<std::size_t>(n_pairs);
  const std::size_t step = std::max<std::size_t>(1, (ds.size() - 10) / n);
  for (std::size_t i = 0; i + 10 < ds.size() && p.depth.size() < n; i += step)
    p.depth.emplace_back(ds.loadDepth(i), ds.loadDepth(i + 10));
  return p;
}

/// The arguments without "NAME VALUE" (the rest go to Google Benchmark), and VALUE as an integer
/// (`fallback` when the option is not given).
inline int takeIntOption(int argc, char** argv, const char* name, int fallback, std::vector<char*>& rest) {
  int value = fallback;
  rest.clear();
  for (int a = 0; a < argc; ++a) {
    if (a + 1 < argc && std::strcmp(argv[a], name) == 0) {
      value = std::atoi(argv[++a]);
      continue;
    }
    rest.push_back(argv[a]);
  }
  return value;
}

}  // namespace gasp::bench
