// Which keyframes a new keyframe is registered to (loop_closure.h), and the parameters' checks.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "gasp/core/error.h"
#include "gasp/slam/loop_closure.h"

namespace {

using gasp::Isometry3;

Isometry3 at(double x, double yaw_deg = 0.0) {
  Isometry3 T = Isometry3::Identity();
  T.linear() = Eigen::AngleAxisd(yaw_deg * M_PI / 180.0, Eigen::Vector3d::UnitY()).toRotationMatrix();  // turns camera z
  T.translation() = Eigen::Vector3d(x, 0, 0);
  return T;
}

}  // namespace

TEST(LoopCandidates, NearestOfTheSamePieceBeyondTheGapAndApartFromEachOther) {
  // Keyframes 0..11 at x = 0, 0.1, ... ; the current one (11) is back at x = 0.04.
  std::vector<Isometry3> T;
  for (int i = 0; i < 11; ++i) T.push_back(at(0.1 * i));
  T.push_back(at(0.04));
  std::vector<std::size_t> keyframes(12), roots(12, 0);
  for (std::size_t i = 0; i < 12; ++i) keyframes[i] = i;
  gasp::LoopClosureParams p;  // radius 0.5, gap 5, 2 candidates
  // Eligible: positions 0..6 (at least 5 keyframes back); within 0.5 m: 0..5. Nearest: 0 and 1
  // (0.04 and 0.06 m), but 1 is within the gap of 0, so the second is 5 (0.46 m).
  EXPECT_EQ(gasp::loopCandidates(keyframes, T, roots, p), (std::vector<std::size_t>{0, 5}));
  p.max_candidates = 1;
  EXPECT_EQ(gasp::loopCandidates(keyframes, T, roots, p), (std::vector<std::size_t>{0}));
  // Another piece is not a loop candidate.
  roots[0] = 0;
  for (std::size_t i = 1; i < 12; ++i) roots[i] = 1;
  EXPECT_EQ(gasp::loopCandidates(keyframes, T, roots, p), (std::vector<std::size_t>{1}));
  // Optical axes too far apart (a roll about the axis would not count).
  T[1] = at(0.1, 60.0);
  EXPECT_EQ(gasp::loopCandidates(keyframes, T, roots, p), (std::vector<std::size_t>{2}));
  T[2] = at(0.2) * Isometry3(Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitZ()));  // rolled 180 deg
  EXPECT_EQ(gasp::loopCandidates(keyframes, T, roots, p), (std::vector<std::size_t>{2}));
  // Too few keyframes for the gap: none.
  EXPECT_TRUE(gasp::loopCandidates({0, 1, 2}, T, roots, p).empty());
  EXPECT_TRUE(gasp::loopCandidates({}, T, roots, p).empty());
  EXPECT_THROW(gasp::loopCandidates({0, 40}, T, roots, p), gasp::Error);
}

TEST(RelocalisationCandidates, TheLatestKeyframesOfOtherPieces) {
  const std::vector<std::size_t> keyframes{0, 3, 6, 9, 12, 15, 18};
  std::vector<std::size_t> roots(19, 0);
  for (std::size_t i = 10; i < 19; ++i) roots[i] = 10;  // frames 10.. are a piece of their own
  gasp::LoopClosureParams p;  // 3 candidates
  EXPECT_EQ(gasp::relocalisationCandidates(keyframes, roots, p), (std::vector<std::size_t>{9, 6, 3}));
  // Three pieces: the latest keyframe of each other piece comes first.
  for (std::size_t i = 13; i < 19; ++i) roots[i] = 13;  // 0-9 | 10-12 | 13-18 (current)
  EXPECT_EQ(gasp::relocalisationCandidates(keyframes, roots, p), (std::vector<std::size_t>{12, 9, 6}));
  for (std::size_t i = 10; i < 19; ++i) roots[i] = 10;
  p.relocalisation_candidates = 0;
  EXPECT_TRUE(gasp::relocalisationCandidates(keyframes, roots, p).empty());
  p.relocalisation_candidates = 3;
  std::fill(roots.begin(), roots.end(), 0);
  EXPECT_TRUE(gasp::relocalisationCandidates(keyframes, roots, p).empty());  // one piece
}

TEST(SlamParams, InvalidValuesAreNamed) {
  const auto message = [](const gasp::SlamParams& p) {
    try {
      gasp::validate(p);
    } catch (const gasp::Error& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  // One change to the defaults at a time, each on a fresh copy.
  const auto with = [&](auto change) {
    gasp::SlamParams p;
    change(p);
    return message(p);
  };
  EXPECT_EQ(with([](gasp::SlamParams&) {}), "(no error)");
  EXPECT_NE(with([](gasp::SlamParams& p) { p.loop.search_radius_m = -1; }).find("search_radius_m"), std::string::npos);
  EXPECT_NE(with([](gasp::SlamParams& p) { p.loop.gate_chi2 = std::nan(""); }).find("gate_chi2"), std::string::npos);
  EXPECT_NE(with([](gasp::SlamParams& p) { p.loop.min_keyframe_gap = 0; }).find("min_keyframe_gap"), std::string::npos);
  EXPECT_NE(with([](gasp::SlamParams& p) { p.odometry.keyframe_angle_deg = 0; }).find("keyframe_angle_deg"),
            std::string::npos);
  EXPECT_NE(with([](gasp::SlamParams& p) { p.graph.max_iterations = 0; }).find("max_iterations"), std::string::npos);
  EXPECT_NE(with([](gasp::SlamParams& p) { p.lidar.patch_area_m2 = 0; }).find("patch_area_m2"), std::string::npos);
}
