// The tracking path of a sequence (trackViews(), pair_registration.h): dense rounds from a
// predicted pose and the certificate, on the simulator's exact truth.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "gasp/pipeline/pair_registration.h"
#include "synthetic_pairs.h"

using namespace gasp;

namespace {

using test::makePair;
using test::Pair;
using test::rotationErrorDeg;
using test::translationError;

}  // namespace

TEST(TrackViews, FromAPredictionNearTheTruthReachesTheWholePipelinesAccuracy) {
  // Consecutive frames of the room (30 Hz), the prediction 2 cm and 1 deg off the truth, as a
  // constant-velocity prediction one frame ahead is: the dense rounds alone bring it within
  // 1 cm / 0.5 deg, as the whole pipeline does, with no association.
  for (const auto& [from, to] : {std::pair{10, 11}, std::pair{20, 21}, std::pair{40, 41}}) {
    const Pair p = makePair("room", from, to);
    const Isometry3 off = Eigen::Translation3d(0.012, -0.01, 0.012) *
                          Eigen::AngleAxisd(1.0 * M_PI / 180.0, Eigen::Vector3d(1, 2, 0).normalized());
    const PairResult t = trackViews(p.a, p.b, off * p.T_b_a, PairParams{});
    ASSERT_TRUE(t.pose.success) << from << " -> " << to << ": " << t.pose.reason;
    EXPECT_LT(translationError(p, t), 0.01) << from << " -> " << to;
    EXPECT_LT(rotationErrorDeg(p, t), 0.5) << from << " -> " << to;
    EXPECT_TRUE(t.association.associations.empty());
    EXPECT_EQ(t.timings.association_ms, 0.0);
    const PairResult whole = registerViews(p.a, p.b);
    ASSERT_TRUE(whole.pose.success) << whole.pose.reason;
    std::printf("%d -> %d: tracking path %.4f m / %.3f deg, whole pipeline %.4f m / %.3f deg off\n", from, to,
                translationError(p, t), rotationErrorDeg(p, t), translationError(p, whole), rotationErrorDeg(p, whole));
  }
}

TEST(TrackViews, AWrongPredictionGivesNoWrongPose) {
  // A prediction half a metre and 20 deg off: the dense rounds cannot reach the truth from there;
  // whatever they end at, the certificate claims no pose beyond 5 cm / 2 deg.
  for (const auto& [from, to] : {std::pair{10, 11}, std::pair{20, 21}, std::pair{40, 41}}) {
    const Pair p = makePair("room", from, to);
    const Isometry3 off = Eigen::Translation3d(0.4, 0.2, -0.2) *
                          Eigen::AngleAxisd(20.0 * M_PI / 180.0, Eigen::Vector3d(0, 1, 0));
    const PairResult t = trackViews(p.a, p.b, off * p.T_b_a, PairParams{});
    if (t.pose.success) {
      EXPECT_LT(translationError(p, t), 0.05) << from << " -> " << to;
      EXPECT_LT(rotationErrorDeg(p, t), 2.0) << from << " -> " << to;
    } else {
      EXPECT_FALSE(t.pose.reason.empty());
    }
  }
}

TEST(TrackViews, ViewsThatCannotFixAPoseGiveTheViewChecksVerdict) {
  const Pair p = makePair("plane", 10, 11);
  PairParams full_only;
  full_only.certify.partial_poses = false;
  const PairResult t = trackViews(p.a, p.b, p.T_b_a, full_only);
  EXPECT_FALSE(t.pose.estimated());
  EXPECT_TRUE(t.pose.degenerate);
  EXPECT_NE(t.pose.reason.find("degenerate scene"), std::string::npos) << t.pose.reason;
  PairParams no_rounds;
  no_rounds.refine.dense.rounds = 0;
  EXPECT_FALSE(trackViews(makePair("room", 10, 11).a, makePair("room", 10, 11).b, p.T_b_a, no_rounds).pose.estimated());
}
