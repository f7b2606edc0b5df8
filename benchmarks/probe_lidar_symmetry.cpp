// A probe for a rule against the quarter-turn wrong poses of symmetric scenes (the LiDAR study,
// docs/experiments/2026-11-29-lidar-pairs.md section 9): for each pair's claimed pose, its
// quarter, half and three-quarter turns about the target's principal patch-normal axes (the
// eigenvectors of the area-weighted sum of n n^T) through the mapped source patches' centroid,
// the translation then voted along each axis (patches facing along it in both views, the offset of
// their planes, 5 cm bins), each refined by trackViews() and compared with the claimed pose's
// likelihood (compareAlternative(): log L(claimed) - log L(alternative), claimed or not).
//   build/ci/bin/probe_lidar_symmetry DIR I J [I J ...]   (DIR: gasp-simulate --sensor lidarNN's folder)
// Prints each alternative's error against the truth and the likelihood comparison, with the
// patches that land on measured depth under both poses, under the claimed one and under the turn
// (the comparison counts only the first: study section 10).
//   PROBE_FREESPACE=1 build/ci/bin/probe_lidar_symmetry DIR I J ...: instead, for each claimed
// pose, a free-space test on the returns (each return against the plane of the other sweep's
// return nearest its direction, a 5 range-sigma gate): the shares of violations and occluded
// samples both ways (study section 10).
#include <mrpt/obs/CObservationRotatingScan.h>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>
#include "gasp/core/tum_trajectory.h"
#include "gasp/pipeline/pose_likelihood.h"
#include "gasp/pipeline/range_view.h"
#include "gasp/pipeline/returns_stage.h"
#include "gasp/pipeline/symmetric_turns.h"
#include "gasp/rawlog/range_scan.h"
#include "gasp/rawlog/rawlog_objects.h"

using gasp::Isometry3;
static double deg(const Isometry3& e) { return Eigen::AngleAxisd(e.linear()).angle() * 180.0 / M_PI; }


// The free-space test on the returns: each return of `from` (with the target's return of nearest
// direction carrying a normal) against the target's plane along its own ray.
struct ReturnShares { int consistent = 0, violations = 0, occluded = 0; };
static ReturnShares returnsFreeSpace(const gasp::SweepReturns& from, const gasp::SweepReturns& to, const Isometry3& T_to_from, double gate) {
  ReturnShares out;
  for (int r = 0; r < from.rows(); ++r)
    for (int c = 0; c < from.cols(); ++c) {
      const Eigen::Vector3d& p = from.point(r, c);
      if (!p.allFinite()) continue;
      const Eigen::Vector3d q = T_to_from * p;
      const int i = to.lookUp(q, 2);
      if (i < 0) continue;
      const Eigen::Vector3d dir = q.normalized();
      const Eigen::Vector3d& pt = to.point(i);
      const Eigen::Vector3d& n = to.normal(i);
      if (std::acos(std::min(1.0, dir.dot(pt.normalized()))) > to.halfCellRad()) continue;
      const double denom = n.dot(dir);
      if (std::abs(denom) < std::cos(80.0 * M_PI / 180.0)) continue;
      const double d = q.norm() - n.dot(pt) / denom;
      if (std::abs(d) <= gate) ++out.consistent;
      else if (d > 0) ++out.occluded;
      else ++out.violations;
    }
  return out;
}

int main(int argc, char** argv) {
  if (argc < 4 || argc % 2 != 0) {
    std::fprintf(stderr, "usage: probe_lidar_symmetry DIR I J [I J ...]\n");
    return 2;
  }
  const std::string dir = argv[1];
  std::vector<gasp::RangeScan> sweeps;
  gasp::RawlogObjects objects(dir + "/lidar.rawlog");
  while (const auto o = objects.next())
    if (const auto s = std::dynamic_pointer_cast<mrpt::obs::CObservationRotatingScan>(o)) sweeps.push_back(gasp::rangeScanFrom(*s));
  const gasp::Trajectory truth = gasp::readTumTrajectory(dir + "/lidar_groundtruth.txt");
  const gasp::PairParams p = gasp::lidarPairParams();
  for (int a = 2; a + 1 < argc; a += 2) {
    const int i = std::atoi(argv[a]), j = std::atoi(argv[a + 1]);
    if (i < 0 || j < 0 || i >= static_cast<int>(sweeps.size()) || j >= static_cast<int>(sweeps.size()) ||
        truth.size() != sweeps.size()) {
      std::fprintf(stderr, "%s: sweeps 0 to %zu with one truth pose each\n", dir.c_str(), sweeps.size() - 1);
      return 1;
    }
    const gasp::DepthView vs = gasp::makeRangeView(sweeps[i], p.segment, p.returns);
    const gasp::DepthView vt = gasp::makeRangeView(sweeps[j], p.segment, p.returns);
    const gasp::PairResult r = gasp::registerViews(vs, vt, p);
    const Isometry3 T_true = truth[j].T_world_camera.inverse() * truth[i].T_world_camera;
    const Isometry3 e0 = T_true.inverse() * r.pose.T_target_source;
    std::printf("pair %d -> %d: claimed %d, %.1f cm %.2f deg off\n", i, j, r.pose.success, 100 * e0.translation().norm(), deg(e0));
    if (!r.pose.success) continue;
    {
      const Eigen::AngleAxisd aa(r.pose.T_target_source.linear() * T_true.linear().transpose());
      std::printf("  error rotation in the target's frame: %.2f deg about (%.3f, %.3f, %.3f)\n", aa.angle() * 180 / M_PI, aa.axis().x(), aa.axis().y(), aa.axis().z());
      for (const gasp::SymmetricTurn& turn : gasp::symmetricTurns(vs, vt, r.pose.T_target_source))
        std::printf("  turn %d about (%.3f, %.3f, %.3f)\n", turn.degrees, turn.axis.x(), turn.axis.y(), turn.axis.z());
    }
    if (std::getenv("PROBE_DISTINCT")) {
      // The verified associations each symmetric turn also explains (its source patch lands on a
      // target patch facing the same way within a loose gate), and the fewest left over.
      const auto& ps = vs.segmentation.patches;
      const auto& pt = vt.segmentation.patches;
      const double gate = std::atof(std::getenv("PROBE_DISTINCT"));
      auto explained = [&](const Isometry3& T, int k) {
        const Eigen::Vector3d c = T * ps[k].centroid;
        const Eigen::Vector3d n = T.linear() * ps[k].normal;
        for (const gasp::SurfacePatch& t : pt) {
          if (n.dot(t.normal) < std::cos(20.0 * M_PI / 180.0)) continue;
          const Eigen::Vector3d d = c - t.centroid;
          const double along = std::abs(d.dot(t.normal));
          if (along > gate) continue;
          if ((d - d.dot(t.normal) * t.normal).norm() > t.radius() + ps[k].radius()) continue;
          return true;
        }
        return false;
      };
      int least = 1 << 30, worst_deg = 0;
      for (const gasp::SymmetricTurn& turn : gasp::symmetricTurns(vs, vt, r.pose.T_target_source)) {
        int distinct = 0;
        for (const auto& v : r.verified) distinct += explained(turn.T_target_source, v.a) ? 0 : 1;
        if (distinct < least) least = distinct, worst_deg = turn.degrees;
      }
      int self = 0;
      for (const auto& v : r.verified) self += explained(r.pose.T_target_source, v.a) ? 1 : 0;
      std::printf("distinct %d %d %s verified %zu self %d inliers %d least %d turn %d\n", i, j,
                  100 * e0.translation().norm() <= 5 && deg(e0) <= 0.5 ? "right" : (100 * e0.translation().norm() <= 20 && deg(e0) <= 5 ? "coarse" : "wrong"),
                  r.verified.size(), self, static_cast<int>(r.pose.inliers.size()), least, worst_deg);
      continue;
    }
    if (std::getenv("PROBE_FREESPACE")) {
      const ReturnShares fa = returnsFreeSpace(*vs.returns, *vt.returns, r.pose.T_target_source, 5 * 0.02);
      const ReturnShares fb = returnsFreeSpace(*vt.returns, *vs.returns, r.pose.T_target_source.inverse(), 5 * 0.02);
      auto ratio = [](const ReturnShares& x) { return double(x.violations) / std::max(1, x.consistent + x.violations + x.occluded); };
      auto occ = [](const ReturnShares& x) { return double(x.occluded) / std::max(1, x.consistent + x.violations + x.occluded); };
      std::printf("freespace %d %d %s violations %.4f %.4f occluded %.3f %.3f samples %d %d\n", i, j,
                  100 * e0.translation().norm() <= 5 && deg(e0) <= 0.5 ? "right" : "wrong", ratio(fa), ratio(fb), occ(fa), occ(fb),
                  fa.consistent + fa.violations + fa.occluded, fb.consistent + fb.violations + fb.occluded);
      continue;
    }
    for (const gasp::SymmetricTurn& turn : gasp::symmetricTurns(vs, vt, r.pose.T_target_source)) {
        const Isometry3& start = turn.T_target_source;
        const gasp::PairResult t = gasp::trackViews(vs, vt, start, p);
        const Isometry3 e = T_true.inverse() * t.pose.T_target_source;
        const Isometry3 es = T_true.inverse() * start;
        if (!t.pose.success) {
          gasp::RegistrationResult alt = t.pose;  // the dense rounds' pose, claimed or not
          alt.success = true, alt.partial = false, alt.degenerate = false;
          if (!alt.T_target_source.matrix().allFinite()) alt.T_target_source = start;
          const Isometry3 ea = T_true.inverse() * alt.T_target_source;
          const gasp::Uniqueness u = gasp::compareAlternative(vs, vt, r.pose, alt, 2.0 * p.hypothesise.pose.ransac.inlier.distance_m, p.certify);
          gasp::RegistrationResult st;
          st.success = true, st.T_target_source = start;
          const gasp::Uniqueness u2 = gasp::compareAlternative(vs, vt, r.pose, st, 2.0 * p.hypothesise.pose.ransac.inlier.distance_m, p.certify);
          gasp::PoseLikelihoodParams lk;
          lk.pixel_step = p.certify.visibility.pixel_step;
          const int common = gasp::logLikelihoodRatio(vs, vt, r.pose.T_target_source, alt.T_target_source, lk).patches;
          const int own = gasp::logLikelihoodRatio(vs, vt, r.pose.T_target_source, r.pose.T_target_source, lk).patches;
          const int its = gasp::logLikelihoodRatio(vs, vt, alt.T_target_source, alt.T_target_source, lk).patches;
          std::printf("  turn %d: unclaimed alternative %.1f cm %.2f deg off truth: tested %d log-ratio %.1f se %.1f take %d refused %d; its start: tested %d log-ratio %.1f se %.1f; patches landing: both %d, claimed %d, turn %d\n",
                      turn.degrees, 100 * ea.translation().norm(), deg(ea), u.tested, u.log_ratio, u.standard_error, u.take_alternative, u.refused,
                      u2.tested, u2.log_ratio, u2.standard_error, common, own, its);
        }
        if (!t.pose.success) {
          std::printf("  turn %d: start %.0f cm %.1f deg off; not claimed (%s)\n", turn.degrees,
                      100 * es.translation().norm(), deg(es), t.pose.reason.substr(0, 60).c_str());
          continue;
        }
        const gasp::Uniqueness u = gasp::compareAlternative(vs, vt, r.pose, t.pose, 2.0 * p.hypothesise.pose.ransac.inlier.distance_m, p.certify);
        std::printf("  turn %d: claimed, %.1f cm %.2f deg off truth; tested %d log-ratio(claimed - alt) %.1f se %.1f take_alt %d refused %d\n",
                    turn.degrees, 100 * e.translation().norm(), deg(e), u.tested, u.log_ratio, u.standard_error, u.take_alternative, u.refused);
      }
  }
}
