#include "gasp/mrpt/ObservationMatcher_GASP.h"

#include <mrpt/core/exceptions.h>
#include <mrpt/obs/CObservation3DRangeScan.h>

#include <Eigen/Geometry>
#include <chrono>

#include "gasp/core/error.h"
#include "gasp/core/pose_perturbation.h"
#include "gasp/core/stopwatch.h"
#include "gasp/params/params_io.h"
#include "gasp/registration/partial_pose.h"
#include "gasp/mrpt/pose_covariance.h"
#include "gasp/pipeline/range_view.h"
#include "gasp/rawlog/observation_conversion.h"
#include "gasp/rawlog/range_scan.h"

IMPLEMENTS_MRPT_OBJECT(ObservationMatcher_GASP, ObservationMatcher, gasp)

namespace gasp {

namespace {

const mrpt::obs::CObservation3DRangeScan& asRangeScan(const mrpt::obs::CObservation& o, const char* which) {
  const auto* scan = dynamic_cast<const mrpt::obs::CObservation3DRangeScan*>(&o);
  if (!scan) {
    THROW_EXCEPTION_FMT("ObservationMatcher_GASP: observation %s is a %s; only mrpt::obs::CObservation3DRangeScan "
                        "(RGB-D or range-only), CObservationRotatingScan, CObservationVelodyneScan and CObservationPointCloud are supported",
                        which, o.GetRuntimeClass()->className);
  }
  return *scan;
}

/// Both observations as frames and views, and the pair's parameters for them: depth images with
/// `camera`, two LiDAR sweeps with lidarPairParams(lidar, camera).
struct MatchInput {
  RgbdFrame fa, fb;
  DepthView va, vb;
  PairParams pair;
};

MatchInput matchInput(const mrpt::obs::CObservation& a, const mrpt::obs::CObservation& b, const PairParams& camera,
                      const LidarParams& lidar) {
  MatchInput in;
  const bool sweep_a = isSweepObservation(a), sweep_b = isSweepObservation(b);
  if (sweep_a != sweep_b)
    THROW_EXCEPTION_FMT("ObservationMatcher_GASP: observation a is %s, b %s: both must be of one kind",
                        observationKind(a).c_str(), observationKind(b).c_str());
  // The observations' conversion errors as MRPT's; the views' (gasp::Error) as they are.
  try {
    if (sweep_a) {
      in.fa = sweepFrameFromObservation(a, "observation a");
      in.fb = sweepFrameFromObservation(b, "observation b");
    } else {
      in.fa = frameFromObservation(asRangeScan(a, "a"), "observation a", ColourImage::Skip);  // depth alone
      in.fb = frameFromObservation(asRangeScan(b, "b"), "observation b", ColourImage::Skip);
    }
  } catch (const Error& e) {
    THROW_EXCEPTION_FMT("ObservationMatcher_GASP: %s", e.what());
  }
  if (sweep_a) {
    in.pair = lidarPairParams(lidar, camera);
    in.va = makeRangeView(*in.fa.sweep, in.pair.segment, in.pair.returns);
    in.vb = makeRangeView(*in.fb.sweep, in.pair.segment, in.pair.returns);
  } else {
    in.pair = camera;
    in.va = makeDepthView(in.fa.depth_m, in.fa.depth_intrinsics, in.pair.segment);
    in.vb = makeDepthView(in.fb.depth_m, in.fb.depth_intrinsics, in.pair.segment);
  }
  return in;
}

}  // namespace

void ObservationMatcher_GASP::initialize(const mrpt::containers::yaml& y) {
  PairParams p;
  LidarParams l;
  readPairParams(y, "ObservationMatcher_GASP", p, &l);
  params = p;
  lidar = l;
}

MatchConstraint ObservationMatcher_GASP::match(const mrpt::obs::CObservation& a, const mrpt::obs::CObservation& b,
                                               const std::optional<mrpt::poses::CPose3D>& /*initial_guess*/) const {
  const auto t0 = std::chrono::steady_clock::now();
  const MatchInput in = matchInput(a, b, params, lidar);
  const RgbdFrame &fa = in.fa, &fb = in.fb;
  MatchConstraint c;
  // b is the source, a the target: T_target_source = T_ca_cb (sensor frames).
  const PairResult r = registerViews(in.vb, in.va, in.pair);
  // The finer-scale retry's and the deskewed sweeps' patch indices refer to their own views, not
  // to these views' patches.
  c.finer_scale = r.finer_scale;
  c.deskewed = r.sweep_motion.moving;
  if (!r.retry_views)
    for (const auto& s : r.association.associations) c.associations.emplace_back(s.b, s.a);
  c.inliers = r.pose.num_inliers;
  c.degenerate = r.pose.degenerate;
  c.success = r.pose.success;
  c.partial = r.pose.partial;
  c.reason = r.pose.reason;
  if (r.pose.estimated()) {
    const Isometry3& S_a = fa.T_robot_camera;
    c.T_a_b = toCPose3D(S_a * r.pose.T_target_source * fb.T_robot_camera.inverse());
    c.information = informationInFrame(r.edge_information, S_a);
  }
  if (c.partial) {
    c.free_directions = adjoint(fa.T_robot_camera) * unobservableTwists(r.pose);
    for (Eigen::Index k = 0; k < c.free_directions.cols(); ++k) c.free_directions.col(k).normalize();
  }
  c.time_ms = msSince(t0);
  return c;
}

}  // namespace gasp
