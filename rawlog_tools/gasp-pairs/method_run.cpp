#include "method_run.h"

#include <algorithm>
#include <chrono>

#include "gasp/association/association_picture.h"
#include "gasp/core/error.h"
#include "gasp/core/stopwatch.h"
#include "gasp/pipeline/visibility_check.h"
#ifdef GASP_HAVE_BASELINES
#include "gasp/baselines/icp_polish.h"
#include "gasp/baselines/match_picture.h"
#endif

namespace gasp::pairs {

namespace {

using Clock = std::chrono::steady_clock;

/// The visibility check's counts and ratios of the pose a run reports.
void setVisibility(MethodRun& run, const VisibilityCheck& check) {
  run.violation_ratio = check.violation_ratio;
  run.violation_ratio_lesser = check.violation_ratio_lesser;
  run.violation_blob_share_lesser = check.violation_blob_share_lesser;
  run.violation_blob_share = check.violation_blob_share;
  run.consistent = check.consistent, run.occluded = check.occluded, run.violations = check.violations;
  run.occluded_ratio = check.occluded_ratio;
}

MethodRun runGasp(const std::string& method, std::size_t i, std::size_t j, FrameCache& cache, const MethodSetup& setup,
                  Picture* picture, const std::optional<Isometry3>& T_gt, const std::optional<Isometry3>& T_ref_icp) {
  MethodRun run;
  PairParams params = setup.gasp;
  if (method == "gasp-norefine") {  // RANSAC's pose only: no patch or dense refinement
    params.hypothesise.pose.refine = false;
    params.refine.dense.rounds = 0;
  }
  const auto& va = cache.gaspView(i, params.segment);
  const auto& vb = cache.gaspView(j, params.segment, setup.roll_target_deg);
  const auto t0 = Clock::now();
  const auto r = registerViews(va.view, vb.view, params);
  const double reg_ms = msSince(t0);
  run.estimated = r.pose.success;
  run.T_target_source = r.pose.T_target_source;
  run.reason = r.pose.reason;
  run.partial = r.pose.partial;
  run.uniqueness_log_ratio = r.uniqueness_log_ratio;
  run.alternative_taken = r.alternative_taken;
  if (r.pose.partial) {
    run.free_directions = static_cast<int>(r.pose.unobservable_directions.cols());
    if (T_gt) run.observed = observedError(r.pose, *T_gt);
  }
  run.ms = va.ms + vb.ms + reg_ms;
  run.associations = r.association.associations.size();
  run.inliers = r.pose.num_inliers;
  setVisibility(run, r.visibility);
  run.one_way = r.used_one_way ? 1 : 0;
  run.guided_support = r.guided_support;
  run.finer_scale = r.finer_scale;
  run.slide_moved = r.slide.moved;
  run.dense_terms = r.dense_terms;
  run.dense_rounds = r.dense_rounds_run;
  run.dense_last_step_m = r.dense_last_step_m;
  run.dense_shortened = r.dense_steps_shortened;
  run.dense_stopped = r.dense_line_search_stopped;
  double gicp_ms = 0.0;
#ifdef GASP_HAVE_BASELINES
  if (method == "gasp-gicp" && r.pose.success) {
    // ICP with GASP's start: GICP from GASP's pose, kept when it gives a pose (PCL counts the
    // iteration limit as converged) that passes the same visibility check; otherwise GASP's
    // pose stands (said in the reason). No test of which pose is better.
    const auto t1 = Clock::now();
    const auto g = baselines::polishPose(va.view.depth_m, vb.view.depth_m, va.view.projection.pinhole(), r.pose.T_target_source);
    if (!g.success) {
      run.reason = "GICP: " + g.reason + "; GASP's pose kept";
    } else {
      const auto check = checkVisibility(va.view, vb.view, g.T_target_source, setup.gasp.certify.visibility);
      if (check.passed) {
        run.T_target_source = g.T_target_source;
        setVisibility(run, check);
      } else {
        run.reason = "GICP's pose failed the visibility check (" + check.reason + "); GASP's pose kept";
      }
    }
    gicp_ms = msSince(t1);
    run.ms += gicp_ms;
  }
#endif
  // The views r's patch indices refer to (the finer-scale retry's when it gave the estimate).
  const auto [pva, pvb] = viewsOf(r, va.view, vb.view);
  if (T_gt) {
    const auto& sa = pva->segmentation;
    const auto& sb = pvb->segmentation;
    run.free_quality = evaluateAssociations(r.association.associations, sa, sb, pvb->depth_m, pvb->projection.pinhole(), *T_gt);
    run.verified_quality = evaluateAssociations(r.verified, sa, sb, pvb->depth_m, pvb->projection.pinhole(), *T_gt);
    if (T_ref_icp)
      run.verified_quality_polished =
          evaluateAssociations(r.verified, sa, sb, pvb->depth_m, pvb->projection.pinhole(), *T_ref_icp);
    run.agreement_truth = depthAgreement(va.view, vb.view, *T_gt, 4);
    if (r.pose.success) run.agreement_estimate = depthAgreement(va.view, vb.view, run.T_target_source, 4);
    if (r.pose.success && method != "gasp-gicp") {  // the information is of GASP's pose
      try {  // a diagnostic: an information it cannot use leaves the columns empty
        run.nees = eval::neesParts(r.pose.T_target_source, *T_gt, r.edge_information);
        run.nees_refinement = eval::nees(r.pose.T_target_source, *T_gt, r.pose.information);
      } catch (const Error&) {
      }
    }
  }
  run.stage_ms = {{"segmentation", va.ms + vb.ms + r.timings.retry_segmentation_ms},
                  {"association", r.timings.association_ms},
                  {"ransac", r.timings.ransac_ms},
                  {"refinement+check",
                   reg_ms - r.timings.retry_segmentation_ms - r.timings.association_ms - r.timings.ransac_ms}};
  if (method == "gasp-gicp" && r.pose.success) run.stage_ms["gicp+check"] = gicp_ms;
  if (picture) {  // the verified associations (what GASP hands its user), or the free ones
    const auto& drawn = setup.picture_free ? r.association.associations : r.verified;
    std::vector<unsigned char> correct;
    if (T_gt)
      for (const auto& a : drawn)
        correct.push_back(isSameSurface(pva->segmentation.patches[static_cast<std::size_t>(a.a)],
                                        pvb->segmentation.patches[static_cast<std::size_t>(a.b)], *T_gt));
    AssociationPictureOptions options;
    options.legend = associationLegend(setup.picture_free ? "free" : "verified", drawn.size(), correct);
    picture->image = drawAssociations(pva->depth_m, pva->segmentation, pva->projection.pinhole(), pvb->depth_m,
                                      pvb->segmentation, pvb->projection.pinhole(), drawn, correct, options);
    picture->shown = drawn.size();
    picture->correct = static_cast<std::size_t>(std::count(correct.begin(), correct.end(), 1));
  }
  return run;
}

#ifdef GASP_HAVE_BASELINES
/// ICP without a start: GICP from the identity (icp_polish.h: voxel-sampled clouds, 5 cm
/// correspondence gate), then the visibility check every method's pose must pass. The depth as
/// the baselines get it (undistorted where the lens is; never deskewed).
MethodRun runGicp(std::size_t i, std::size_t j, FrameCache& cache, const MethodSetup& setup,
                  const std::optional<Isometry3>& T_gt) {
  MethodRun run;
  DepthView va, vb;  // the check reads only depth and intrinsics
  va.depth_m = cache.rgbd(i).depth_m, va.projection = cache.rgbd(i).intrinsics;
  vb.depth_m = cache.rgbd(j).depth_m, vb.projection = cache.rgbd(j).intrinsics;
  const auto t0 = Clock::now();
  const auto g = baselines::polishPose(va.depth_m, vb.depth_m, va.projection.pinhole(), Isometry3::Identity());
  const double icp_ms = msSince(t0);
  run.T_target_source = g.T_target_source;
  if (!g.success) {
    run.reason = "GICP: " + g.reason;
  } else {
    const auto check = checkVisibility(va, vb, g.T_target_source, setup.gasp.certify.visibility);
    setVisibility(run, check);
    run.estimated = check.passed;
    if (!check.passed) run.reason = check.reason;
  }
  if (run.estimated && T_gt) run.agreement_estimate = depthAgreement(va, vb, run.T_target_source, 4);
  run.ms = msSince(t0);
  run.stage_ms = {{"gicp", icp_ms}, {"check", run.ms - icp_ms}};
  return run;
}

/// A feature baseline: keypoints described once per frame, matched, RANSAC, the visibility check.
MethodRun runBaseline(const std::string& method, std::size_t i, std::size_t j, FrameCache& cache,
                      const MethodSetup& setup, Picture* picture, const std::optional<Isometry3>& T_gt) {
  MethodRun run;
  const auto m = baselines::parseMethod(method);
  const auto& ka = cache.described(i, m, setup.baseline);
  const auto& kb = cache.described(j, m, setup.baseline);
  const auto t0 = Clock::now();
  const auto r = baselines::registerDescribed(cache.rgbd(i), cache.rgbd(j), ka, kb, setup.baseline);
  const double reg_ms = msSince(t0);
  run.estimated = r.pose.success;
  run.T_target_source = r.pose.T_target_source;
  run.reason = r.pose.reason;
  run.ms = ka.describe_ms + kb.describe_ms + reg_ms;
  run.associations = r.matches.size();
  run.inliers = r.pose.num_inliers;
  setVisibility(run, r.visibility);
  run.stage_ms = {{"description", ka.describe_ms + kb.describe_ms},
                  {"matching", r.timings.match_ms},
                  {"ransac", r.timings.ransac_ms},
                  {"check", r.timings.check_ms}};
  if (picture) {
    std::vector<cv::Point2f> ma, mb;
    std::vector<unsigned char> correct;
    for (std::size_t k = 0; k < r.matches.size(); ++k) {
      ma.push_back(r.source.pixels[static_cast<std::size_t>(r.matches[k].a)]);
      mb.push_back(r.target.pixels[static_cast<std::size_t>(r.matches[k].b)]);
      if (T_gt) correct.push_back((*T_gt * r.correspondences[k].p_source - r.correspondences[k].p_target).norm() <= 0.05);
    }
    auto image = [&](std::size_t f) {
      const auto& v = cache.rgbd(f);
      if (!v.bgr.empty()) return v.bgr;
      cv::Mat grey;  // no colour: the depth, scaled to 0..5 m
      v.depth_m.convertTo(grey, CV_8U, 255.0 / 5.0);
      return grey;
    };
    picture->image =
        baselines::drawKeypointMatches(image(i), image(j), r.source.pixels, r.target.pixels, ma, mb, correct);
    picture->shown = r.matches.size();
    picture->correct = static_cast<std::size_t>(std::count(correct.begin(), correct.end(), 1));
  }
  return run;
}
#endif

}  // namespace

std::vector<std::string> knownMethods() {
  std::vector<std::string> m{"gasp", "gasp-norefine"};
#ifdef GASP_HAVE_BASELINES
  for (auto b : baselines::allMethods()) m.push_back(baselines::methodName(b));
  m.push_back("gicp");       // PCL's GICP from the identity: ICP without a start
  m.push_back("gasp-gicp");  // GICP started from GASP's pose: ICP with GASP's start
#endif
  return m;
}

bool isGasp(const std::string& method) {
  return method == "gasp" || method == "gasp-norefine" || method == "gasp-gicp";
}

bool needsColour(const std::string& method) { return method == "cshot" || method == "sift" || method == "dsift"; }

MethodRun runMethod(const std::string& method, std::size_t i, std::size_t j, FrameCache& cache,
                    const MethodSetup& setup, Picture* picture, const std::optional<Isometry3>& T_gt,
                    const std::optional<Isometry3>& T_ref_icp) {
  if (isGasp(method)) return runGasp(method, i, j, cache, setup, picture, T_gt, T_ref_icp);
#ifdef GASP_HAVE_BASELINES
  if (method == "gicp") return runGicp(i, j, cache, setup, T_gt);
  return runBaseline(method, i, j, cache, setup, picture, T_gt);
#else
  throw Error("gasp-pairs: method " + method + " is not in this build");
#endif
}

std::optional<Isometry3> polishWithGicp([[maybe_unused]] FrameCache& cache, [[maybe_unused]] std::size_t i,
                                        [[maybe_unused]] std::size_t j, [[maybe_unused]] const SuperpixelParams& params,
                                        [[maybe_unused]] const Isometry3& T_init) {
#ifdef GASP_HAVE_BASELINES
  const auto& va = cache.gaspView(i, params).view;
  const auto& vb = cache.gaspView(j, params).view;
  const auto r = baselines::polishPose(va.depth_m, vb.depth_m, va.projection.pinhole(), T_init);
  if (r.success) return r.T_target_source;
#endif
  return std::nullopt;
}

}  // namespace gasp::pairs
