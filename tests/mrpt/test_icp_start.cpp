// What GASP is for in MRPT: giving mrpt::slam::CICP a start. Frames as CObservation3DRangeScan,
// their points in CSimplePointsMap (robot frames), MRPT's 3D ICP run from the identity and from
// the pose ObservationMatcher_GASP gives (docs/mrpt.md, "Giving MRPT's ICP a start"; skipped
// without the real data).
#include <gtest/gtest.h>
#include <mrpt/maps/CSimplePointsMap.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/poses/CPose3DPDFGaussian.h>
#include <mrpt/slam/CICP.h>

#include <cmath>
#include <random>
#include <cstdio>
#include <string>

#include "gasp/core/tum_dataset.h"
#include "gasp/mrpt/observation_matcher.h"
#include "gasp/rawlog/observation_conversion.h"
#include "gasp/rawlog/tum_to_rawlog.h"
#include "gasp_test_data.h"

using namespace gasp;

namespace {

/// The observation's points in its robot frame, a random sixteenth of the pixels (a fixed seed; not a
/// regular grid, whose pattern would be the same in both views).
mrpt::maps::CSimplePointsMap pointsOf(mrpt::obs::CObservation3DRangeScan& obs) {
  mrpt::maps::CSimplePointsMap map;
  mrpt::obs::T3DPointsProjectionParams params;
  params.takeIntoAccountSensorPoseOnRobot = true;
  params.decimation = 1;
  mrpt::maps::CSimplePointsMap all;
  obs.unprojectInto(all, params);
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> keep(0, 15);
  for (std::size_t k = 0; k < all.size(); ++k) {
    float x, y, z;
    all.getPoint(k, x, y, z);
    if (keep(rng) == 0) map.insertPoint(x, y, z);
  }
  return map;
}

/// MRPT's 3D ICP (point to point) of b's points onto a's from `start` (a guess of T_a_b): a 10 cm
/// correspondence gate halved at each convergence down to 1 cm, at most 100 iterations.
Isometry3 icp(const mrpt::maps::CSimplePointsMap& a, const mrpt::maps::CSimplePointsMap& b, const Isometry3& start,
              double& goodness) {
  mrpt::slam::CICP icp;
  icp.options.maxIterations = 100;
  icp.options.thresholdDist = 0.1;
  icp.options.thresholdAng = 0.0;
  icp.options.smallestThresholdDist = 0.01;
  icp.options.corresponding_points_decimation = 1;
  mrpt::slam::CICP::TReturnInfo info;
  const auto pdf = icp.Align3DPDF(&a, &b, mrpt::poses::CPose3DPDFGaussian(toCPose3D(start)), info);
  goodness = info.goodness;
  return pdf ? fromCPose3D(pdf->getMeanVal()) : start;
}

struct Outcome {
  Isometry3 truth, gasp, icp_alone, icp_from_gasp, icp_from_truth;
  double goodness_alone = 0, goodness_from_gasp = 0, goodness_from_truth = 0;
};

double metres(const Isometry3& truth, const Isometry3& T) { return translationNorm(truth.inverse() * T); }
double degrees(const Isometry3& truth, const Isometry3& T) { return rotationAngle(truth.inverse() * T) * 180 / M_PI; }

/// Frames i -> j of a TUM folder: the truth (robot frames), GASP's pose, ICP from the identity and
/// from GASP's pose, printed.
Outcome run(const std::string& dir, std::size_t i, std::size_t j) {
  const auto ds = TumDataset::open(dir);
  const RgbdFrame fa = frameFromTum(ds, i, false), fb = frameFromTum(ds, j, false);
  const auto a = observationFromFrame(fa), b = observationFromFrame(fb);
  Outcome o;
  // frameFromTum mounts the optical camera looking along the robot's +X.
  o.truth = fa.T_robot_camera * relativePose(*ds.frame(i).T_world_camera, *ds.frame(j).T_world_camera) *
            fb.T_robot_camera.inverse();
  const auto pa = pointsOf(*a), pb = pointsOf(*b);
  EXPECT_GT(pa.size(), 1000u);
  o.icp_alone = icp(pa, pb, Isometry3::Identity(), o.goodness_alone);
  const MatchConstraint c = createObservationMatcher("gasp::ObservationMatcher_GASP")->match(*a, *b);
  EXPECT_TRUE(c.success) << c.reason;
  o.gasp = fromCPose3D(c.T_a_b);
  o.icp_from_gasp = icp(pa, pb, o.gasp, o.goodness_from_gasp);
  o.icp_from_truth = icp(pa, pb, o.truth, o.goodness_from_truth);
  std::printf("%s %zu -> %zu: motion %.3f m %.1f deg; ICP from the identity %.3f m %.2f deg off (goodness %.2f); "
              "GASP %.3f m %.2f deg; ICP from GASP %.3f m %.2f deg (goodness %.2f); ICP from the reference "
              "%.3f m %.2f deg (goodness %.2f)\n",
              dir.c_str(), i, j, translationNorm(o.truth), rotationAngle(o.truth) * 180 / M_PI,
              metres(o.truth, o.icp_alone), degrees(o.truth, o.icp_alone), o.goodness_alone, metres(o.truth, o.gasp),
              degrees(o.truth, o.gasp), metres(o.truth, o.icp_from_gasp), degrees(o.truth, o.icp_from_gasp),
              o.goodness_from_gasp, metres(o.truth, o.icp_from_truth), degrees(o.truth, o.icp_from_truth),
              o.goodness_from_truth);
  // Where the ICP poses end, measured from the identity (the views' relative pose if the camera
  // had not moved).
  std::printf("  their distance from the identity: ICP from the identity %.3f m %.2f deg, from GASP %.3f m %.2f deg, "
              "from the reference %.3f m %.2f deg\n",
              translationNorm(o.icp_alone), rotationAngle(o.icp_alone)*180/M_PI, translationNorm(o.icp_from_gasp), rotationAngle(o.icp_from_gasp)*180/M_PI, translationNorm(o.icp_from_truth), rotationAngle(o.icp_from_truth)*180/M_PI);
  return o;
}

}  // namespace

TEST(IcpStart, GaspGivesMrptsIcpAStartItCannotFindAlone) {
  // fr1_xyz 0 -> 30: 0.36 m and 6 deg apart, a cluttered desk.
  GASP_REQUIRE_DATA(dir, "tum/fr1_xyz");
  const Outcome o = run(dir, 0, 30);
  EXPECT_LT(metres(o.truth, o.icp_from_gasp), 0.03);
  EXPECT_LT(degrees(o.truth, o.icp_from_gasp), 1.5);
  EXPECT_GT(o.goodness_from_gasp, 0.8);
  EXPECT_TRUE(metres(o.truth, o.icp_alone) > 0.1 || degrees(o.truth, o.icp_alone) > 3.0)
      << "MRPT's ICP found this pose from the identity: the pair no longer shows what GASP is for";
}

TEST(IcpStart, OnAFloorDominatedViewGaspIsNearTheReference) {
  // fr3_cabinet_kf 0 -> 2 (0.29 m, 12 deg): one cabinet on a floor. GASP's pose is near the
  // reference. MRPT's point-to-point ICP ends near the identity from it (and from the reference);
  // that is printed, not asserted (a property of that ICP, not of GASP; docs/mrpt.md).
  GASP_REQUIRE_DATA(dir, "tum/fr3_cabinet_kf");
  const Outcome o = run(dir, 0, 2);
  EXPECT_LT(metres(o.truth, o.gasp), 0.03);
  EXPECT_LT(degrees(o.truth, o.gasp), 3.0);
}
