// gasp-associate: patch associations and the relative pose between two depth views.
//   gasp-associate --tum DIR --from I --to J [--out PICTURE.png] [--params FILE] [options]
//   gasp-associate --depth-a A.png --depth-b B.png [--intrinsics fr1|fr2|fr3|ros|FILE] [--depth-scale 5000]
//   gasp-associate --rawlog FILE.rawlog --from I --to J [--sensor LABEL] [--gt CAMERA_TRAJECTORY.txt] [options]
// I and J are frame indices in depth.txt order, or (--rawlog) the I-th and J-th
// CObservation3DRangeScan of the rawlog, counting from 0. Prints the patch count of each view, the number
// of associations, time per stage, the pose T_b_a (maps A's camera frame into B's) with its
// inliers and information, and, where both frames have ground truth, `precision:`, `density:`
// (definitions in gasp/association/association_quality.h) and the pose error. Writes a picture:
// both views side by side, associated patches in the same colour, others grey, lines for a
// sample of associations (green correct, red wrong, white when there is no ground truth): the
// verified associations, or with --free the free ones.
// Exit codes: 0 pose estimated, 1 bad input, 2 usage error, 3 no association, 4 associations but
// no pose estimate (the reason is printed).
#include <CLI/CLI.hpp>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <optional>

#include "gasp/association/association_picture.h"
#include "gasp/association/association_quality.h"
#include "gasp/core/depth_image.h"
#include "gasp/core/error.h"
#include "gasp/core/image_file.h"
#include "gasp/core/tum_trajectory.h"
#include "gasp/core/tum_dataset.h"
#include "gasp/pipeline/pair_registration.h"
#include "gasp/pipeline/rolling_shutter_deskew.h"
#include "gasp/rawlog/rawlog_reader.h"
#include "cli.h"
#include "params_options.h"

int main(int argc, char** argv) {
  CLI::App app{"gasp-associate: patch-to-patch associations and the relative pose between two depth views, from geometry alone"};
  std::string tum_dir, depth_a_path, depth_b_path, intrinsics_arg, out_path;
  std::size_t from = 0, to = 0;
  double depth_scale = gasp::kTumDepthUnitsPerMetre;
  gasp::tools::ParamsOptions params_options;
  gasp::SlamParams all_params;
  if (!params_options.preload(argc, argv, all_params)) return 1;
  gasp::PairParams& params = all_params.odometry.pair;  // the params file's sections segment to retry
  auto* tum = app.add_option("--tum", tum_dir, "TUM RGB-D folder");
  std::string rawlog_path, gt_path;
  auto* rawlog = app.add_option("--rawlog", rawlog_path,
                                "an MRPT rawlog: views A and B are its --from-th and --to-th CObservation3DRangeScan "
                                "(counting from 0; other objects are skipped)")
                     ->excludes(tum);
  auto* from_opt = app.add_option("--from", from, "index of view A in depth.txt order (--rawlog: among its 3D range scans)")
                       ->check(gasp::tools::atLeast(0));
  auto* to_opt = app.add_option("--to", to, "index of view B in depth.txt order (--rawlog: among its 3D range scans)")
                     ->check(gasp::tools::atLeast(0));
  std::string sensor_label;
  app.add_option("--sensor", sensor_label, "with --rawlog: count only the scans with this sensorLabel")->needs(rawlog);
  app.add_option("--gt", gt_path,
                 "with --rawlog: a TUM trajectory of the camera (optical frame) poses, looked up at the scans' "
                 "timestamps (nearest within 0.02 s), e.g. the OUT_groundtruth.txt gasp-tum2rawlog writes")
      ->needs(rawlog);
  auto* da = app.add_option("--depth-a", depth_a_path, "view A: a 16-bit depth PNG")->excludes(tum)->excludes(rawlog);
  auto* db = app.add_option("--depth-b", depth_b_path, "view B: a 16-bit depth PNG")->excludes(tum)->excludes(rawlog);
  da->needs(db);
  db->needs(da);
  app.add_option("--depth-scale", depth_scale, "raw depth units per metre (with --depth-a/-b)")
      ->capture_default_str()
      ->check(gasp::tools::above(0))
      ->excludes(rawlog);
  double gt_offset = 0.0;
  app.add_option("--gt-offset", gt_offset,
                 "with --tum: look ground truth up at depth timestamp + OFFSET [s] (as gasp-pairs)")
      ->capture_default_str()
      ->check(gasp::tools::within(-60, 60))
      ->excludes(rawlog);
  bool no_undistort = false;
  app.add_flag("--no-undistort", no_undistort, "resample depth (and rgb) to the pinhole camera when the intrinsics have lens distortion (fr1, fr2: default); this flag uses the images as stored")->excludes(rawlog);
  app.add_option("--intrinsics", intrinsics_arg, "fr1|fr2|fr3|ros or an intrinsics file (default: the folder's; ros for PNGs)")->excludes(rawlog);
  app.add_option("--out", out_path, "association picture (default: associations_I_J.png, or associations.png for PNGs)");
  bool picture_free = false;
  app.add_flag("--free", picture_free,
               "the picture shows the free associations (before any pose) instead of the verified ones");
  bool refine = true;
  app.add_flag("!--no-refine", refine,
               "RANSAC pose only: no patch refinement and no dense rounds (hypothesise.refine = false, "
               "refine.dense_rounds = 0)");
  gasp::DeskewParams deskew;
  app.add_option("--rolling-shutter", deskew.readout_s,
                 "deskew both views for a rolling shutter with this readout time [s] (first row to last; negative: "
                 "bottom-up; TUM's Kinect: 0.03), with the velocity from GASP's pose between each frame's neighbours")
      ->needs(tum)
      ->capture_default_str();
  params_options.add(app);
  try {
    app.parse(argc, argv);
    if ((from_opt->count() > 0 || to_opt->count() > 0) && tum_dir.empty() && rawlog_path.empty())
      throw CLI::ValidationError("--from and --to need --tum or --rawlog");
    if ((!tum_dir.empty() || !rawlog_path.empty()) && (from_opt->count() == 0 || to_opt->count() == 0))
      throw CLI::ValidationError("--tum and --rawlog need --from I and --to J");
    if (!std::isfinite(deskew.readout_s) || std::abs(deskew.readout_s) > 1.0)
      throw CLI::ValidationError("--rolling-shutter must be a finite time of at most 1 s (either sign)");
    if (!out_path.empty()) gasp::requireImageWriter(out_path, "--out picture");
  } catch (const CLI::ParseError& e) {
    return gasp::tools::usageExit(app, e);  // --help: 0; any usage error: 2
  } catch (const gasp::Error& e) {
    std::cerr << "error: " << gasp::exceptionMessage(e) << '\n';
    return 2;
  }
  if (!refine) {  // both refinements off: RANSAC's pose
    params.hypothesise.pose.refine = false;
    params.refine.dense.rounds = 0;
  }
  if (const int code = params_options.printIfAsked(all_params); code >= 0) return code;
  if (tum_dir.empty() && rawlog_path.empty() && depth_a_path.empty()) {
    std::cerr << "error: give --tum DIR --from I --to J, --rawlog FILE --from I --to J, or --depth-a A.png --depth-b B.png\n";
    return 2;
  }
  // The default picture path is known before the work, so it is checked with --out's rules.
  if (out_path.empty())
    out_path = depth_a_path.empty() ? "associations_" + std::to_string(from) + "_" + std::to_string(to) + ".png"
                                    : "associations.png";
  std::vector<std::string> inputs = gasp::tools::tumFolderInputs(tum_dir);
  for (const std::string& f : gasp::tools::rawlogInputs(rawlog_path)) inputs.push_back(f);
  for (const std::string& f : {gt_path, depth_a_path, depth_b_path})
    if (!f.empty()) inputs.push_back(f);
  std::optional<gasp::tools::RunOutputs> outputs;
  try {
    gasp::requireImageWriter(out_path, "--out");
    outputs.emplace(std::vector<std::pair<std::string, std::string>>{{"--out", out_path}}, inputs);  // before the work
  } catch (const gasp::Error& e) {
    std::cerr << "error: " << gasp::exceptionMessage(e) << '\n';
    return 1;
  }
  try {
    cv::Mat depth_a, depth_b;
    gasp::CameraIntrinsics K;
    std::optional<gasp::CameraIntrinsics> K_b;  // view B's own (rawlog scans carry theirs)
    std::optional<gasp::Isometry3> T_b_a_true, T_robot_camera_a, T_robot_camera_b;
    if (!rawlog_path.empty()) {
      // The two scans, read in one pass (the rawlog may be long; only what is needed is kept).
      gasp::RawlogReader reader(rawlog_path);
      std::optional<gasp::RgbdFrame> fa, fb;
      for (std::size_t k = 0; k <= std::max(from, to);) {
        auto f = reader.next();
        if (!f)
          throw gasp::Error(rawlog_path + ": has " + std::to_string(k) + " CObservation3DRangeScan" +
                            (sensor_label.empty() ? std::string() : " of sensor '" + sensor_label + "'") +
                            ", index " + std::to_string(std::max(from, to)) + " asked for (other objects: " +
                            reader.skippedSummary() + ")");
        if (!sensor_label.empty() && f->sensor_label != sensor_label) continue;
        if (k == from) fa = *f;
        if (k == to) fb = std::move(*f);
        ++k;
      }
      depth_a = fa->depth_m, depth_b = fb->depth_m;
      K = fa->depth_intrinsics, K_b = fb->depth_intrinsics;
      T_robot_camera_a = fa->T_robot_camera, T_robot_camera_b = fb->T_robot_camera;
      if (!gt_path.empty()) {
        const gasp::Trajectory gt = gasp::readTumTrajectory(gt_path);
        const auto ia = gasp::findNearest(gt, fa->timestamp, 0.02), ib = gasp::findNearest(gt, fb->timestamp, 0.02);
        if (ia && ib) T_b_a_true = gasp::relativePose(gt[*ib].T_world_camera, gt[*ia].T_world_camera);
        else std::printf("ground_truth: none within 0.02 s of the scans' timestamps in %s\n", gt_path.c_str());
      }
    } else if (!tum_dir.empty()) {
      gasp::TumDataset::Options opt;
      if (!intrinsics_arg.empty()) opt.intrinsics = gasp::CameraIntrinsics::fromPresetOrFile(intrinsics_arg);
      opt.undistort = !no_undistort;
      const auto ds = gasp::TumDataset::open(tum_dir, opt);
      gasp::tools::reportIntrinsics(stdout, ds.intrinsicsSummary(), ds.intrinsicsWarning());
      depth_a = ds.loadDepth(from);
      depth_b = ds.loadDepth(to);
      K = ds.intrinsics();
      if (deskew.readout_s != 0.0) {
        // Each view deskewed with the velocity between its neighbours (rolling_shutter_deskew.h).
        auto deskewView = [&](std::size_t i, const char* name, cv::Mat& depth) {
          const auto d = gasp::deskewTumFrame(ds, i, depth, deskew, params);
          if (!d.deskewed) {
            std::printf("rolling_shutter_%s: not deskewed (%s)\n", name, d.reason.c_str());
            return;
          }
          const auto [a, b] = gasp::neighbourFrames(i, ds.size());
          std::printf("rolling_shutter_%s: deskewed, velocity %.3f m/s %.1f deg/s (frames %zu -> %zu)\n", name,
                      d.twist.v_mps.norm(), d.twist.w_radps.norm() * 180.0 / M_PI, a, b);
          depth = d.depth_m;
        };
        deskewView(from, "a", depth_a);
        deskewView(to, "b", depth_b);
      }
      const auto ga = ds.groundTruthOf(from, gt_offset), gb = ds.groundTruthOf(to, gt_offset);
      if (ga && gb) T_b_a_true = gasp::relativePose(*gb, *ga);
    } else {
      K = gasp::CameraIntrinsics::fromPresetOrFile(intrinsics_arg.empty() ? "ros" : intrinsics_arg);
      if (no_undistort) K.distortion.fill(0.0);
      const gasp::Undistortion undistortion(K);
      depth_a = undistortion.applyToDepth(gasp::loadDepth(depth_a_path, depth_scale, K.width, K.height));
      depth_b = undistortion.applyToDepth(gasp::loadDepth(depth_b_path, depth_scale, K.width, K.height));
      K = undistortion.pinhole();
    }
    // Each view resampled to its pinhole camera where its intrinsics carry lens distortion.
    const auto [va, vb] = K_b && *K_b != K ? std::make_pair(gasp::makeDepthView(depth_a, K, params.segment),
                                                            gasp::makeDepthView(depth_b, *K_b, params.segment))
                                           : gasp::makeDepthViews(depth_a, depth_b, K, params.segment);
    const auto r = gasp::registerViews(va, vb, params);
    // The views r's patch indices refer to: the finer-scale retry's when it found the estimate.
    const auto [pva, pvb] = gasp::viewsOf(r, va, vb);
    const auto& s = r.association.stats;
    std::printf("patches_a: %zu\npatches_b: %zu\nassociations: %zu\n", pva->segmentation.patches.size(),
                pvb->segmentation.patches.size(), r.association.associations.size());
    // With the retry, the stage times are summed over both attempts; the association breakdown is
    // that of the attempt whose associations are shown.
    std::printf("time_ms%s: segmentation %.1f + %.1f, association %.1f (features %.1f, kd-tree %.1f, matching %.1f), "
                "ransac %.1f, refinement %.1f, dense+check %.1f\n",
                r.retried ? " (both attempts; the breakdown in brackets: the attempt shown)" : "",
                va.segmentation.timings.total(), vb.segmentation.timings.total(), r.timings.association_ms,
                s.features_ms, s.tree_ms, s.matching_ms, r.timings.ransac_ms, r.timings.refine_ms, r.timings.dense_ms);
    if (r.finer_scale)
      std::printf("finer_scale_retry: yes (the default scale found no estimate; segmented again at %g x the patch "
                  "area in %.1f ms; the patches, associations, picture and scores here are of those views)\n",
                  params.retry.finer_area_factor, r.timings.retry_segmentation_ms);
    else if (r.retried)
      std::printf("finer_scale_retry: no estimate either (segmented again at %g x the patch area in %.1f ms)\n",
                  params.retry.finer_area_factor, r.timings.retry_segmentation_ms);
    std::printf("comparisons: %zu of %zu without KD-tree, %zu cut early, %zu gated out, %zu not mutual\n",
                s.comparisons, s.comparisons_full, s.cut_early, s.gated_out, s.not_mutual);
    if (T_b_a_true) {
      const auto q = gasp::evaluateAssociations(r.association.associations, pva->segmentation, pvb->segmentation,
                                                pvb->depth_m, pvb->projection.pinhole(), *T_b_a_true);
      std::printf("correct: %d\nwith_true_partner: %d\nprecision: %.3f\ndensity: %.3f\n", q.correct,
                  q.with_true_partner, q.precision(), q.density());
    } else {
      std::printf("ground truth: not available for both frames\n");
    }
    // The picture: the verified associations (what GASP hands its user), or with --free the free ones.
    const auto& drawn = picture_free ? r.association.associations : r.verified;
    std::vector<unsigned char> drawn_correct;
    if (T_b_a_true)
      for (const auto& a : drawn)
        drawn_correct.push_back(gasp::isSameSurface(pva->segmentation.patches[static_cast<std::size_t>(a.a)],
                                                    pvb->segmentation.patches[static_cast<std::size_t>(a.b)], *T_b_a_true));
    gasp::AssociationPictureOptions picture_options;
    picture_options.legend = gasp::associationLegend(picture_free ? "free" : "verified", drawn.size(), drawn_correct);
    if (!picture_free && !r.pose.success) picture_options.legend += " (no pose: --free draws the free ones)";
    const cv::Mat picture = gasp::drawAssociations(pva->depth_m, pva->segmentation, pva->projection.pinhole(), pvb->depth_m,
                                                   pvb->segmentation, pvb->projection.pinhole(), drawn, drawn_correct,
                                                   picture_options);
    gasp::writeImage(outputs->at("--out"), picture, "picture");
    std::printf("picture: %s\npicture_legend: %s\n", out_path.c_str(), picture_options.legend.c_str());
    if (r.association.associations.empty()) {
      std::printf("no associations: %s\n",
                  r.association.reason.empty() ? r.pose.reason.c_str() : r.association.reason.c_str());
      std::printf("pose: none (%s)\n", r.pose.reason.c_str());
      return 3;
    }
    std::printf("inliers: %d\none_way_fallback: %s\nguided_support: %d\n", r.pose.num_inliers,
                r.used_one_way ? "yes" : "no", r.guided_support);
    if (std::isfinite(r.uniqueness_log_ratio))  // the certificate compared the pose with RANSAC's distinct alternative
      std::printf("uniqueness: log-likelihood ratio %.1f over a distinct alternative%s\n", r.uniqueness_log_ratio,
                  r.alternative_taken ? " (the alternative was taken)" : "");
    if (r.pose.partial) {  // observed directions only: printed, but no full pose (exit 4)
      const auto& T = r.pose.T_target_source;
      const Eigen::Quaterniond q(T.linear());
      std::printf("partial_pose_T_b_a: %.5f %.5f %.5f %.6f %.6f %.6f %.6f (tx ty tz qx qy qz qw; free directions "
                  "arbitrary)\nfree_directions: %d\n",
                  T.translation().x(), T.translation().y(), T.translation().z(), q.x(), q.y(), q.z(), q.w(),
                  static_cast<int>(r.pose.unobservable_directions.cols()));
    }
    if (!r.pose.success) {
      std::printf("pose: none (%s)\n", r.pose.reason.c_str());
      return 4;
    }
    const auto& T = r.pose.T_target_source;
    const Eigen::Quaterniond qt(T.linear());
    std::printf("pose_T_b_a: %.5f %.5f %.5f %.6f %.6f %.6f %.6f (tx ty tz qx qy qz qw)\n", T.translation().x(),
                T.translation().y(), T.translation().z(), qt.x(), qt.y(), qt.z(), qt.w());
    if (T_robot_camera_a && T_robot_camera_b) {
      // The same pose between the scans' robot frames (their sensorPose honoured). MRPT's edge
      // A -> B (and CICP's result) is its inverse, the pose of B's robot frame in A's.
      const gasp::Isometry3 R = *T_robot_camera_b * T * T_robot_camera_a->inverse();
      const Eigen::Quaterniond qr(R.linear());
      std::printf("pose_robot_b_a: %.5f %.5f %.5f %.6f %.6f %.6f %.6f (tx ty tz qx qy qz qw; robot frame of A in B's; "
                  "MRPT's edge A -> B is its inverse)\n",
                  R.translation().x(), R.translation().y(), R.translation().z(), qr.x(), qr.y(), qr.z(), qr.w());
    }
    std::printf("residual_rms_m: %.4f\ninformation_diag: ", r.pose.rms_residual_m);
    for (int i = 0; i < 6; ++i) std::printf("%.4g%s", r.pose.information(i, i), i < 5 ? " " : " (tx ty tz rx ry rz)\n");
    {  // The standard deviations a pose graph gets (the edge information: with the model error).
      const Eigen::Matrix<double, 6, 6> C = r.edge_information.inverse();
      std::printf("edge_sigma: %.4f %.4f %.4f m, %.3f %.3f %.3f deg (tx ty tz rx ry rz; model error %g m, %g deg)\n",
                  std::sqrt(C(0, 0)), std::sqrt(C(1, 1)), std::sqrt(C(2, 2)), std::sqrt(C(3, 3)) * 180.0 / M_PI,
                  std::sqrt(C(4, 4)) * 180.0 / M_PI, std::sqrt(C(5, 5)) * 180.0 / M_PI, params.certify.model_error.sigma_t_m,
                  params.certify.model_error.sigma_r_deg);
    }
    std::printf("visibility_violations: %.3f (other direction %.3f)\nvisibility_occluded: %.3f\n",
                r.visibility.violation_ratio, r.visibility.violation_ratio_lesser, r.visibility.occluded_ratio);
    std::printf("dense_rounds: %d (last step %.1f mm; line search: %d steps shortened%s)\n", r.dense_rounds_run,
                1000.0 * r.dense_last_step_m, r.dense_steps_shortened,
                r.dense_line_search_stopped ? ", stopped the rounds" : "");
    std::printf("dense_terms: %d\nedge_paired_share: %.3f\nwide_edge_pose: %s\n", r.dense_terms, r.edge_paired_share,
                r.wide_edge_pose ? "yes" : "no");
    std::printf("slide_scan: %s\n", r.slide.summary().c_str());
    std::printf("verified_associations: %zu\n", r.verified.size());
    if (T_b_a_true) {
      const auto q = gasp::evaluateAssociations(r.verified, pva->segmentation, pvb->segmentation, pvb->depth_m, pvb->projection.pinhole(), *T_b_a_true);
      std::printf("verified_precision: %.3f\nverified_density: %.3f\n", q.precision(), q.density());
    }
    if (T_b_a_true) {
      const gasp::Isometry3 E = T_b_a_true->inverse() * T;
      std::printf("pose_error: %.4f m %.3f deg\n", gasp::translationNorm(E), gasp::rotationAngle(E) * 180.0 / M_PI);
    }
  } catch (const std::exception& e) {  // gasp::Error, and anything a library throws
    std::cerr << "error: " << gasp::exceptionMessage(e) << '\n';
    return 1;
  }
  return 0;
}
