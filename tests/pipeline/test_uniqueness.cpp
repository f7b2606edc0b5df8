// The certificate's uniqueness test (certify_stage.h) and the likelihood it compares poses by
// (pose_likelihood.h), on the simulator's exact truth.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>

#include "gasp/core/error.h"
#include "gasp/pipeline/certify_stage.h"
#include "gasp/pipeline/pose_likelihood.h"
#include "synthetic_pairs.h"

using namespace gasp;

namespace {

using test::makePair;
using test::Pair;

RegistrationResult fullPose(const Isometry3& T) {
  RegistrationResult r;
  r.success = true;
  r.T_target_source = T;
  return r;
}

const double kDistinct = 0.10;  // twice RANSAC's inlier distance, as the pipeline uses

}  // namespace

TEST(PoseLikelihood, TheTruthExplainsTheViewsBetterThanPosesAFewCentimetresOff) {
  const Pair p = makePair("room", 10, 20);
  const double needed = std::log(CertifyParams{}.min_likelihood_ratio);
  for (const Isometry3& off : {Isometry3(Eigen::Translation3d(0.05, 0, 0)), Isometry3(Eigen::Translation3d(0, 0, 0.05)),
                               Isometry3(Eigen::AngleAxisd(2.0 * M_PI / 180.0, Eigen::Vector3d::UnitY()))}) {
    const LikelihoodRatio r = logLikelihoodRatio(p.a, p.b, p.T_b_a, off * p.T_b_a);
    EXPECT_GT(r.log_ratio, needed);
    EXPECT_GT(r.log_ratio, kUniquenessStandardErrors * r.standard_error);
    EXPECT_GT(r.patches, 500);
    const LikelihoodRatio back = logLikelihoodRatio(p.a, p.b, off * p.T_b_a, p.T_b_a);
    EXPECT_NEAR(back.log_ratio, -r.log_ratio, 1e-9);
    EXPECT_NEAR(back.standard_error, r.standard_error, 1e-9);
  }
  EXPECT_EQ(logLikelihoodRatio(p.a, p.b, p.T_b_a, p.T_b_a).log_ratio, 0.0);
  Isometry3 nan = p.T_b_a;
  nan.translation().x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(logLikelihoodRatio(p.a, p.b, nan, p.T_b_a).patches, 0);
  EXPECT_EQ(logLikelihoodRatio(DepthView{}, DepthView{}, p.T_b_a, p.T_b_a).patches, 0);
}

// One pose's samples kept (poseSamples) and compared with many others give the ratio computed
// afresh to the bit, with the violation charge and the certificate's sampling; the certificate's
// comparison with them gives the same verdict, and refuses samples of another pose.
TEST(PoseLikelihood, OnePosesSamplesKeptGiveTheSameRatiosToTheBit) {
  const Pair p = makePair("room", 10, 20);
  CertifyParams certify;
  certify.violation_nats = std::log(10.0);
  PoseLikelihoodParams params;
  params.violation_nats = certify.violation_nats;
  params.pixel_step = 4;
  const PoseSamples kept = poseSamples(p.a, p.b, p.T_b_a, params);
  for (const Isometry3& off : {Isometry3(Eigen::Translation3d(0.05, 0, 0)), Isometry3(Eigen::Translation3d(0, 0, -0.3)),
                               Isometry3(Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitY())), Isometry3::Identity()}) {
    const LikelihoodRatio fresh = logLikelihoodRatio(p.a, p.b, p.T_b_a, off * p.T_b_a, params);
    const LikelihoodRatio from_kept = logLikelihoodRatio(p.a, p.b, kept, off * p.T_b_a, params);
    EXPECT_EQ(fresh.log_ratio, from_kept.log_ratio);
    EXPECT_EQ(fresh.standard_error, from_kept.standard_error);
    EXPECT_EQ(fresh.patches, from_kept.patches);
    const RegistrationResult chosen = fullPose(p.T_b_a), alternative = fullPose(off * p.T_b_a);
    const Uniqueness u = compareAlternative(p.a, p.b, chosen, alternative, kDistinct, certify);
    const Uniqueness v = compareAlternative(p.a, p.b, chosen, alternative, kDistinct, certify,
                                            samplesForComparison(p.a, p.b, chosen, certify));
    EXPECT_EQ(u.tested, v.tested);
    EXPECT_TRUE(u.log_ratio == v.log_ratio || (std::isnan(u.log_ratio) && std::isnan(v.log_ratio)));
    EXPECT_EQ(u.take_alternative, v.take_alternative);
    EXPECT_EQ(u.refused, v.refused);
  }
  EXPECT_GT(logLikelihoodRatio(p.a, p.b, kept, Eigen::Translation3d(0.05, 0, 0) * p.T_b_a, params).patches, 500);
  EXPECT_THROW(logLikelihoodRatio(p.a, p.b, kept, p.T_b_a, PoseLikelihoodParams{}), Error);  // taken every 4, asked every 8
  EXPECT_THROW(compareAlternative(p.a, p.b, fullPose(p.T_b_a), fullPose(p.T_b_a), kDistinct, certify,
                                  samplesForComparison(p.a, p.b, fullPose(Eigen::Translation3d(0.05, 0, 0) * p.T_b_a), certify)),
               Error);
}

// A sample put in space the other view saw as empty costs violation_nats beyond an outlier; an
// occluded one nothing (pose_likelihood.h). A pose 30 cm towards the target camera puts the
// source's surfaces in front of the target's (past the free-space gate): with the charge the truth
// gains over it, and the certificate's comparison charges the same.
TEST(PoseLikelihood, ASampleInTheOtherViewsFreeSpaceCostsTheViolationCharge) {
  const Pair p = makePair("room", 10, 20);
  const Isometry3 forward = Eigen::Translation3d(0, 0, -0.3) * p.T_b_a;
  PoseLikelihoodParams plain, charged;
  charged.violation_nats = std::log(10.0);
  const LikelihoodRatio r0 = logLikelihoodRatio(p.a, p.b, p.T_b_a, forward, plain);
  const LikelihoodRatio rc = logLikelihoodRatio(p.a, p.b, p.T_b_a, forward, charged);
  std::printf("truth over 30 cm towards the target: %.1f without the charge, %.1f with it\n", r0.log_ratio, rc.log_ratio);
  EXPECT_GT(rc.log_ratio, r0.log_ratio + 20.0);
  EXPECT_EQ(logLikelihoodRatio(p.a, p.b, p.T_b_a, p.T_b_a, charged).log_ratio, 0.0);
  EXPECT_NEAR(logLikelihoodRatio(p.a, p.b, forward, p.T_b_a, charged).log_ratio, -rc.log_ratio, 1e-9);
  // One direction only (a source view without patches adds no terms of its own): the target's
  // samples mapped into the source. Moving the source 30 cm towards the target camera pushes them
  // behind the source's surfaces (occluded: no charge); moving it away pulls them in front
  // (violations: charged).
  DepthView source_only_depth = p.a;
  source_only_depth.segmentation.patches.clear();
  const Isometry3 backward = Eigen::Translation3d(0, 0, 0.3) * p.T_b_a;
  const double gain_forward = logLikelihoodRatio(source_only_depth, p.b, p.T_b_a, forward, charged).log_ratio -
                              logLikelihoodRatio(source_only_depth, p.b, p.T_b_a, forward, plain).log_ratio;
  const double gain_backward = logLikelihoodRatio(source_only_depth, p.b, p.T_b_a, backward, charged).log_ratio -
                               logLikelihoodRatio(source_only_depth, p.b, p.T_b_a, backward, plain).log_ratio;
  std::printf("one direction: the charge adds %.1f against the pose moved towards the target, %.1f away\n",
              gain_forward, gain_backward);
  EXPECT_GT(gain_backward, 20.0);
  EXPECT_LT(gain_forward, 0.25 * gain_backward);
  CertifyParams certify;
  certify.violation_nats = charged.violation_nats;
  EXPECT_NEAR(compareAlternative(p.a, p.b, fullPose(p.T_b_a), fullPose(forward), kDistinct, certify).log_ratio,
              rc.log_ratio, 1e-9);
  certify.violation_nats = -1.0;
  EXPECT_THROW(validate(certify), Error);
}

TEST(Uniqueness, KeepsTheMoreLikelyPoseAndTakesABetterAlternative) {
  const Pair p = makePair("room", 10, 20);
  const RegistrationResult truth = fullPose(p.T_b_a);
  const RegistrationResult slid = fullPose(Eigen::Translation3d(0.15, 0, 0) * p.T_b_a);
  const CertifyParams params;
  const Uniqueness kept = compareAlternative(p.a, p.b, truth, slid, kDistinct, params);
  std::printf("log-likelihood ratio of the truth over a 15 cm slide: %.1f\n", kept.log_ratio);
  EXPECT_TRUE(kept.tested);
  EXPECT_GT(kept.distance_m, 0.14);
  EXPECT_GT(kept.log_ratio, std::log(params.min_likelihood_ratio));
  EXPECT_FALSE(kept.refused);
  EXPECT_FALSE(kept.take_alternative);
  const Uniqueness taken = compareAlternative(p.a, p.b, slid, truth, kDistinct, params);
  EXPECT_TRUE(taken.tested);
  EXPECT_NEAR(taken.log_ratio, -kept.log_ratio, 1e-9);
  EXPECT_TRUE(taken.take_alternative);
  EXPECT_FALSE(taken.refused);
}

TEST(Uniqueness, RefusesWhenNeitherPoseIsEnoughMoreLikely) {
  // One large plane filling both views: a pose slid 20 cm along it explains them as well as the
  // truth, so neither is claimed (a full pose is assumed here; the pipeline would give a partial
  // one). Without noise the two explain every patch equally; with the Kinect's noise the sum of
  // the patch terms differs by tens of nats, within three standard errors.
  for (const bool noise : {false, true}) {
    sim::SimulationOptions o;
    o.scene = "plane";
    if (!noise) o.noise = sim::KinectNoiseModel::exact();
    const sim::Simulation s(o);
    const auto fa = s.frame(10), fb = s.frame(20);
    const DepthView a = makeDepthView(fa.depth, o.intrinsics), b = makeDepthView(fb.depth, o.intrinsics);
    const Isometry3 T = relativePose(fb.T_world_camera, fa.T_world_camera);
    // The plane is x = 3 m in the world: the world's y axis in the target camera lies in it exactly.
    const Eigen::Vector3d along = fb.T_world_camera.linear().transpose() * Eigen::Vector3d::UnitY();
    const Uniqueness u = compareAlternative(a, b, fullPose(T), fullPose(Eigen::Translation3d(0.2 * along) * T),
                                            kDistinct, CertifyParams{});
    std::printf("%s: log-likelihood ratio of the truth over a 20 cm slide along the plane %.1f +- %.1f\n",
                noise ? "Kinect noise" : "no noise", u.log_ratio, u.standard_error);
    EXPECT_TRUE(u.tested) << noise;
    EXPECT_LT(std::abs(u.log_ratio), kUniquenessStandardErrors * u.standard_error + 1e-12) << noise;
    if (!noise) {
      EXPECT_EQ(u.log_ratio, 0.0);
    }
    EXPECT_TRUE(u.refused) << noise;
    EXPECT_FALSE(u.take_alternative) << noise;
    EXPECT_NE(u.reason.find("not unique"), std::string::npos) << u.reason;
  }
}

TEST(Uniqueness, PosesCloserThanTwiceTheInlierDistanceAreNotAlternatives) {
  const Pair p = makePair("room", 10, 20);
  const Uniqueness u = compareAlternative(p.a, p.b, fullPose(p.T_b_a), fullPose(Eigen::Translation3d(0.08, 0, 0) * p.T_b_a),
                                          kDistinct, CertifyParams{});
  EXPECT_FALSE(u.tested);
  EXPECT_TRUE(std::isnan(u.log_ratio));
  CertifyParams off;
  off.min_likelihood_ratio = 0.0;
  EXPECT_FALSE(compareAlternative(p.a, p.b, fullPose(p.T_b_a), fullPose(Eigen::Translation3d(0.3, 0, 0) * p.T_b_a),
                                  kDistinct, off)
                   .tested);
  off.min_likelihood_ratio = 0.5;
  EXPECT_THROW(validate(off), Error);
}

TEST(Uniqueness, APartialPoseMovedAlongItsFreeDirectionsIsTheSamePose) {
  // A bare floor: the pipeline's partial pose leaves the slides along the floor free; the same
  // pose slid 30 cm along the floor differs from it only there.
  const Pair p = makePair("floor_0", 10, 20);
  const PairResult r = registerViews(p.a, p.b);
  ASSERT_TRUE(r.pose.partial) << r.pose.reason;
  const auto plane = dominantPlane(p.b.segmentation);
  ASSERT_TRUE(plane.has_value());
  const Eigen::Vector3d along = plane->normal.unitOrthogonal();
  RegistrationResult slid = r.pose;
  slid.T_target_source = Eigen::Translation3d(0.3 * along) * r.pose.T_target_source;
  const Uniqueness same = compareAlternative(p.a, p.b, r.pose, slid, kDistinct, CertifyParams{});
  EXPECT_FALSE(same.tested) << same.distance_m;
  // Lifted off the floor by 15 cm it is another pose.
  RegistrationResult lifted = r.pose;
  lifted.T_target_source = Eigen::Translation3d(0.15 * plane->normal) * r.pose.T_target_source;
  const Uniqueness other = compareAlternative(p.a, p.b, r.pose, lifted, kDistinct, CertifyParams{});
  EXPECT_TRUE(other.tested);
  EXPECT_FALSE(other.refused);
  EXPECT_GT(other.log_ratio, 0.0);
}
