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
#include "gasp/sim/noise_model.h"
#include "gasp/sim/renderer.h"
#include "synthetic_pairs.h"

namespace {

using namespace gasp;
using test::Pair;

/// The room's frames i and j, frame j rendered with the objects whose names start with `prefix`
/// moved by `shift` (world frame).
Pair pairWithMovedObject(int i, int j, const std::string& prefix, const Eigen::Vector3d& shift) {
  const auto& s = test::simulation("room");
  sim::Scene moved = s.scene();
  int n = 0;
  for (auto& o : moved.objects)
    if (o.name.rfind(prefix, 0) == 0) o.T_world_object.translation() += shift, ++n;
  EXPECT_GT(n, 0) << prefix;
  const auto K = s.options().intrinsics;
  const auto fa = s.frame(i);
  const Isometry3 T_world_b = s.path().poses[static_cast<std::size_t>(j)].T_world_camera;
  const cv::Mat depth_b = sim::sensorDepth(sim::renderFrame(moved, K, T_world_b, j), s.options().noise, K, s.options().seed, j);
  return {makeDepthView(fa.depth, K), makeDepthView(depth_b, K), relativePose(T_world_b, fa.T_world_camera)};
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
    lifted.visibility.max_two_way_violation_ratio = 1.0;
    const PairResult l = registerViews(p.a, p.b, lifted);
    std::printf("%s moved: %s (%s); with the limit lifted: %s, violations %.3f / %.3f (worse / lesser)\n", m.prefix,
                r.pose.success ? "registered" : "no estimate", r.pose.reason.c_str(),
                l.pose.success ? "registered" : "no estimate", l.visibility.violation_ratio,
                l.visibility.violation_ratio_lesser);
    if (r.pose.success) {
      EXPECT_LT(test::translationError(p, r), 0.02) << m.prefix;
      EXPECT_LT(test::rotationErrorDeg(p, r), 1.0) << m.prefix;
    } else {
      EXPECT_NE(r.pose.reason.find("visibility check"), std::string::npos) << r.pose.reason;
    }
    // The one-direction limits alone register each of them right (the check before the two-way limit).
    ASSERT_TRUE(l.pose.success) << m.prefix << ": " << l.pose.reason;
    EXPECT_LT(test::translationError(p, l), 0.02) << m.prefix;
  }
}
