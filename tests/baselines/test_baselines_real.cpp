// Every baseline on real data (fr1_desk9): an easy pair of consecutive frames must give the
// ground-truth pose within 5 cm / 3 deg, and -- because consecutive frames move only ~14 mm /
// 1.3 deg, so that even "no motion" would pass -- at least 20 matches and 10% of them must agree
// with the ground truth (random matches: a few percent), and a wider pair (0 -> 8, 0.11 m /
// 8.7 deg) must be recovered within 5 cm and half its rotation (the identity fails both).
// A broken descriptor, matcher or back-projection cannot pass as a weak one.
#include <gtest/gtest.h>

#include <cstdio>
#include <ostream>

#include "gasp/baselines/baseline_registration.h"
#include "gasp/core/tum_dataset.h"
#include "gasp_test_data.h"

namespace gb = gasp::baselines;

namespace gasp::baselines {
// Readable test names in ctest's list ("GetParam() = fpfh").
inline void PrintTo(BaselineMethod m, std::ostream* os) { *os << methodName(m); }
}  // namespace gasp::baselines

namespace {

class BaselineOnRealPair : public ::testing::TestWithParam<gb::BaselineMethod> {};

gb::RgbdImage load(const gasp::TumDataset& ds, std::size_t i) {
  return {ds.loadDepth(i), ds.loadRgb(i), ds.intrinsics()};
}

/// Bounds: 5 cm and max_r_deg, or half the true rotation when max_r_deg < 0.
void checkPair(const gasp::TumDataset& ds, std::size_t i, std::size_t j, gb::BaselineMethod method, double max_r_deg) {
  const gasp::Isometry3 T_gt = gasp::relativePose(*ds.frame(j).T_world_camera, *ds.frame(i).T_world_camera);
  const auto r = gb::registerWithBaseline(load(ds, i), load(ds, j), method);
  // Matches consistent with the ground truth: the mapped source keypoint within 5 cm of its partner.
  std::size_t correct = 0;
  for (const auto& c : r.correspondences) correct += (T_gt * c.p_source - c.p_target).norm() <= 0.05;
  const double share = r.correspondences.empty() ? 0.0 : double(correct) / double(r.correspondences.size());
  std::printf("  ms: describe %.0f match %.0f ransac %.0f check %.0f\n", r.timings.describe_ms, r.timings.match_ms,
              r.timings.ransac_ms, r.timings.check_ms);
  std::printf("%s %zu->%zu: keypoints %zu/%zu, matches %zu, gt-consistent %.2f, inliers %d, %s\n",
              gb::methodName(method).c_str(), i, j, r.source.size(), r.target.size(), r.matches.size(), share,
              r.pose.num_inliers, r.pose.success ? "estimate" : r.pose.reason.c_str());
  ASSERT_TRUE(r.pose.success) << r.pose.reason;
  const gasp::Isometry3 E = T_gt.inverse() * r.pose.T_target_source;
  const double t_err = gasp::translationNorm(E), r_err = gasp::rotationAngle(E) * 180.0 / M_PI;
  std::printf("  error %.4f m %.3f deg (ground-truth motion %.4f m %.3f deg)\n", t_err, r_err,
              gasp::translationNorm(T_gt), gasp::rotationAngle(T_gt) * 180.0 / M_PI);
  EXPECT_LE(t_err, 0.05);
  EXPECT_LE(r_err, max_r_deg >= 0 ? max_r_deg : 0.5 * gasp::rotationAngle(T_gt) * 180.0 / M_PI);
  EXPECT_GE(correct, 20u);
  EXPECT_GE(share, 0.1);  // random matches: a few percent
}

}  // namespace

TEST_P(BaselineOnRealPair, RecoversConsecutiveAndWiderFr1Desk9Pairs) {
  GASP_REQUIRE_DATA(dir, "tum/fr1_desk9");
  const auto ds = gasp::TumDataset::open(dir);
  ASSERT_GE(ds.size(), 9u);
  checkPair(ds, 0, 1, GetParam(), 3.0);   // the acceptance bound: 5 cm / 3 deg
  checkPair(ds, 0, 8, GetParam(), -1.0);   // half the true rotation: 4.3 deg
}

INSTANTIATE_TEST_SUITE_P(AllBaselines, BaselineOnRealPair, ::testing::ValuesIn(gb::allMethods()),
                         [](const auto& param_info) { return gb::methodName(param_info.param); });
