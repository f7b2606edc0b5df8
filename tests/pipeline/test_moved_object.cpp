// An object that moved between two views of a static room (a chair pushed, a ball rolled away):
// its samples violate the other view's free space from both views, which the visibility check's
// two-way limit (max_two_way_violation_ratio, 5 %) takes for a wrong alignment once the object
// covers enough of the overlap. What a user must be able to rely on: a right pose or no estimate,
// never a wrong one; and with the limit lifted, the right pose. Measured (docs/pipeline.md
// "Violations seen from both views"): the chair pushed 0.6 m between the wide-baseline frames
// 3 -> 9 violates 8.9 % / 7.2 % of the overlap from the two views and gives no estimate; the big
// ball (out of the second view: one direction only) and the table pushed 0.5 m (1.7 % / 1.1 %)
// are registered.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "gasp/pipeline/pair_registration.h"
#include "gasp/sim/object_move.h"
#include "gasp/sim/simulation.h"
#include "synthetic_pairs.h"

namespace {

using namespace gasp;
using test::Pair;

/// The room's frames i and j, with the objects whose names start with `prefix` moved by `shift`
/// (world frame) from frame j on (gasp::sim object moves).
Pair pairWithMovedObject(int i, int j, const std::string& prefix, const Eigen::Vector3d& shift) {
  sim::SimulationOptions o;
  o.moves = {sim::ObjectMove{prefix, shift, 0.0, j}};
  const sim::Simulation s(o);
  const auto K = s.options().intrinsics;
  const auto fa = s.frame(i), fb = s.frame(j);
  return {makeDepthView(fa.depth, K), makeDepthView(fb.depth, K), relativePose(fb.T_world_camera, fa.T_world_camera)};
}

struct Moved {
  const char* prefix;
  double dx, dy;
};

}  // namespace

TEST(MovedObject, GivesTheRightPoseOrNoEstimateNeverAWrongOne) {
  for (const Moved m : {Moved{"chair", 0.0, -0.6}, Moved{"big_ball", 0.6, -0.9}, Moved{"table", 0.0, -0.5}}) {
    const Pair p = pairWithMovedObject(3, 9, m.prefix, Eigen::Vector3d(m.dx, m.dy, 0.0));
    const PairResult r = registerViews(p.a, p.b);
    PairParams lifted;
    lifted.certify.visibility.max_two_way_violation_ratio = 1.0;
    const PairResult l = registerViews(p.a, p.b, lifted);
    std::printf("%s moved: %s (%s); with the limit lifted: %s, violations %.3f / %.3f (worse / lesser)\n", m.prefix,
                r.pose.success ? "registered" : "no estimate", r.pose.reason.c_str(),
                l.pose.success ? "registered" : "no estimate", l.visibility.violation_ratio,
                l.visibility.violation_ratio_lesser);
    if (r.pose.success) {
      EXPECT_LT(test::translationError(p, r), 0.02) << m.prefix;
      EXPECT_LT(test::rotationErrorDeg(p, r), 1.0) << m.prefix;
      EXPECT_FALSE(r.visibility_refused) << m.prefix;
    } else {
      EXPECT_NE(r.pose.reason.find("visibility check"), std::string::npos) << r.pose.reason;
      EXPECT_TRUE(r.visibility_refused) << r.pose.reason;  // the odometry's cue for a scene change
    }
    // The one-direction limits alone register each of them right (the check before the two-way limit).
    ASSERT_TRUE(l.pose.success) << m.prefix << ": " << l.pose.reason;
    EXPECT_LT(test::translationError(p, l), 0.02) << m.prefix;
  }
}
