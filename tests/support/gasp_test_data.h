#pragma once
// Test helpers: the real-data folder (../shared/data by default, GASP_DATA_DIR overrides) and a
// scratch folder per test.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <string>
#include <vector>

namespace gasp::test {

/// The shared real-data folder, or nullopt when it does not exist.
inline std::optional<std::string> sharedDataDir() {
  const char* env = std::getenv("GASP_DATA_DIR");
  const std::string dir = (env && *env) ? env : GASP_DATA_DIR_DEFAULT;
  if (std::filesystem::is_directory(dir)) return dir;
  return std::nullopt;
}

/// DATA_DIR/sub if it exists.
inline std::optional<std::string> sharedDataPath(const std::string& sub) {
  const auto dir = sharedDataDir();
  if (!dir) return std::nullopt;
  const std::string p = *dir + "/" + sub;
  if (!std::filesystem::exists(p)) return std::nullopt;
  return p;
}

/// A fresh, empty scratch folder named after the running test.
inline std::string scratchDir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::string dir = std::string(GASP_TEST_TMP_DIR) + "/" + info->test_suite_name() + "." +
                          info->name();
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

/// The whole content of a file ("" when it cannot be read).
inline std::string fileText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

/// The names of a folder's entries, sorted (to see that nothing was left beside an output).
inline std::vector<std::string> namesIn(const std::string& dir) {
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace gasp::test

/// Declares std::string VAR = path of SUB in the real-data folder, or skips the test saying why.
#define GASP_REQUIRE_DATA(VAR, SUB)                                                         \
  const auto VAR##_opt_ = ::gasp::test::sharedDataPath(SUB);                                \
  if (!VAR##_opt_) {                                                                        \
    GTEST_SKIP() << "real data '" << (SUB) << "' not found under "                         \
                 << (std::getenv("GASP_DATA_DIR") ? std::getenv("GASP_DATA_DIR")           \
                                                  : GASP_DATA_DIR_DEFAULT)                  \
                 << " (set GASP_DATA_DIR or the CMake option GASP_DATA_DIR); skipping";   \
  }                                                                                         \
  const std::string VAR = *VAR##_opt_
