#include "gasp/mrpt/ObservationMatcher_GASP.h"

#include <mrpt/core/exceptions.h>
#include <mrpt/obs/CObservation3DRangeScan.h>

#include <Eigen/Geometry>
#include <chrono>
#include <set>

#include "gasp/core/error.h"
#include "gasp/rawlog/observation_conversion.h"

IMPLEMENTS_MRPT_OBJECT(ObservationMatcher_GASP, ObservationMatcher, gasp)

namespace gasp {

namespace {

const mrpt::obs::CObservation3DRangeScan& asRangeScan(const mrpt::obs::CObservation& o, const char* which) {
  const auto* scan = dynamic_cast<const mrpt::obs::CObservation3DRangeScan*>(&o);
  if (!scan) {
    THROW_EXCEPTION_FMT("ObservationMatcher_GASP: observation %s is a %s; only mrpt::obs::CObservation3DRangeScan "
                        "(RGB-D or range-only) is supported",
                        which, o.GetRuntimeClass()->className);
  }
  return *scan;
}

/// Adjoint of S for xi = [translation; rotation]: Exp(Ad_S xi) = S Exp(xi) S^-1.
Eigen::Matrix<double, 6, 6> adjoint(const Isometry3& S) {
  const Eigen::Matrix3d R = S.linear();
  const Eigen::Vector3d t = S.translation();
  Eigen::Matrix3d tx;
  tx << 0, -t.z(), t.y(), t.z(), 0, -t.x(), -t.y(), t.x(), 0;
  Eigen::Matrix<double, 6, 6> A = Eigen::Matrix<double, 6, 6>::Zero();
  A.topLeftCorner<3, 3>() = R;
  A.topRightCorner<3, 3>() = tx * R;
  A.bottomRightCorner<3, 3>() = R;
  return A;
}

}  // namespace

void ObservationMatcher_GASP::initialize(const mrpt::containers::yaml& y) {
  PairParams p;
  if (!y.isNullNode() && !y.empty()) {
    if (!y.isMap()) THROW_EXCEPTION("ObservationMatcher_GASP: parameters must be a YAML map");
    static const std::set<std::string> known{"target_patch_area_m2", "neighbourhood_k", "candidates", "lambda",
                                             "mutual_check", "min_inliers", "dense_rounds", "refine"};
    for (const auto& [key, value] : y.asMap()) {
      const auto name = key.as<std::string>();
      if (!known.count(name)) THROW_EXCEPTION_FMT("ObservationMatcher_GASP: unknown parameter '%s'", name.c_str());
    }
    p.superpixels.target_patch_area_m2 = y.getOrDefault<double>("target_patch_area_m2", p.superpixels.target_patch_area_m2);
    p.association.feature_sets.neighbourhood.k = y.getOrDefault<int>("neighbourhood_k", p.association.feature_sets.neighbourhood.k);
    p.association.candidates = y.getOrDefault<int>("candidates", p.association.candidates);
    p.association.lambda = y.getOrDefault<double>("lambda", p.association.lambda);
    p.association.mutual_check = y.getOrDefault<bool>("mutual_check", p.association.mutual_check);
    p.pose.ransac.min_inliers = y.getOrDefault<int>("min_inliers", p.pose.ransac.min_inliers);
    p.dense_rounds = y.getOrDefault<int>("dense_rounds", p.dense_rounds);
    p.refine = y.getOrDefault<bool>("refine", p.refine);
  }
  try {
    validate(p);
  } catch (const Error& e) {
    THROW_EXCEPTION_FMT("ObservationMatcher_GASP: invalid parameters: %s", e.what());
  }
  params = p;
}

MatchConstraint ObservationMatcher_GASP::match(const mrpt::obs::CObservation& a, const mrpt::obs::CObservation& b,
                                               const std::optional<mrpt::poses::CPose3D>& /*initial_guess*/) const {
  const auto t0 = std::chrono::steady_clock::now();
  const auto& scan_a = asRangeScan(a, "a");
  const auto& scan_b = asRangeScan(b, "b");
  MatchConstraint c;
  RgbdFrame fa, fb;
  try {
    fa = frameFromObservation(scan_a, "observation a");
    fb = frameFromObservation(scan_b, "observation b");
  } catch (const Error& e) {
    THROW_EXCEPTION_FMT("ObservationMatcher_GASP: %s", e.what());
  }
  const DepthView va = makeDepthView(fa.depth_m, fa.depth_intrinsics, params.superpixels);
  const DepthView vb = makeDepthView(fb.depth_m, fb.depth_intrinsics, params.superpixels);
  // b is the source, a the target: T_target_source = T_ca_cb (camera frames).
  const PairResult r = registerViews(vb, va, params);
  for (const auto& s : r.association.associations) c.associations.emplace_back(s.b, s.a);
  c.inliers = r.pose.num_inliers;
  c.degenerate = r.pose.degenerate;
  c.success = r.pose.success;
  c.reason = r.pose.reason;
  if (c.success) {
    const Isometry3& S_a = fa.T_robot_camera;
    c.T_a_b = toCPose3D(S_a * r.pose.T_target_source * fb.T_robot_camera.inverse());
    // xi_robot = Ad(S_a) xi_camera, so I_robot = Ad^-T I_camera Ad^-1.
    const Eigen::Matrix<double, 6, 6> Ad_inv = adjoint(S_a.inverse());
    c.information = Ad_inv.transpose() * r.pose.information * Ad_inv;
  }
  c.time_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return c;
}

}  // namespace gasp
