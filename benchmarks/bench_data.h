#pragma once
// Where benchmarks find the real data: $GASP_DATA_DIR, else the CMake option's default.
#include <cstdlib>
#include <string>

namespace gasp::bench {

inline std::string dataDir() {
  const char* env = std::getenv("GASP_DATA_DIR");
  return (env && *env) ? env : GASP_DATA_DIR_DEFAULT;
}

}  // namespace gasp::bench
