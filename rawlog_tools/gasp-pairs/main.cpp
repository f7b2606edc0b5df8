// gasp-pairs: the paper's pair benchmark on a TUM folder, GASP beside the feature baselines.
//   gasp-pairs --tum DIR [--skips 10,20,30,40] [--starts-every N]
//              [--method gasp,gasp-norefine,fpfh,shot,cshot,sift,dsift,gicp,gasp-gicp] [--csv OUT.csv]
//              [--pairs-csv OUT_pairs.csv] [--max-pairs N] [--picture I,J [--picture-prefix P] [--picture-format png|jpg] [--pictures-only] [--picture-free]]
//              [--params FILE] [--print-params]
// Pairs (i, i + skip) from start frames 0, N, 2N, ... (indices in depth.txt order); for each pair
// and method a relative pose is estimated and compared with ground truth. Prints one table row per
// skip and method (definitions in gasp/eval/pair_protocol.h and docs/evaluation.md); progress goes
// to stderr. The baselines (fpfh, shot, cshot, sift, dsift; gasp/baselines/) and PCL's GICP from
// the identity (gicp) or from GASP's pose (gasp-gicp) exist when the build has GASP_BUILD_BASELINES.
// Colour methods (cshot, sift, dsift) are not run on pairs where a frame has no rgb: those rows say
// "n/a (no rgb)" and count the pairs left out.
// Time per pair = description of both views (segmentation for GASP; measured once per frame and
// charged to every pair using it) + association or matching + pose stages; image loading excluded.
// --roll-target DEG turns each pair's target image by a quarter or half turn (the camera rolled
// about its optical axis; GASP's methods only) and scores against the reference rolled alike.
// Exit codes: 0 done, 1 bad input, 2 usage error, 4 no pair with ground truth.
// The pieces: frame_cache.h (views per frame), method_run.h (one method on one pair),
// pair_reference.h (the reference), deskew_filter.h (--rolling-shutter), rgb_check.h
// (--rgb-rotation-check), pairs_csv.h (--pairs-csv), pairs_table.h (the printed table).
#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>

#include "cli.h"
#include "params_options.h"
#include "deskew_filter.h"
#include "frame_cache.h"
#include "gasp/core/error.h"
#include "gasp/core/image_file.h"
#include "gasp/core/stopwatch.h"
#include "gasp/core/tum_dataset.h"
#include "gasp/eval/pair_protocol.h"
#include "gasp/pipeline/pair_registration.h"
#include "gasp/pipeline/rolling_shutter_deskew.h"
#include "method_run.h"
#include "pair_reference.h"
#include "pairs_csv.h"
#include "pairs_table.h"
#include "rgb_check.h"
#ifdef GASP_HAVE_BASELINES
#include "gasp/baselines/baseline_registration.h"
#include "gasp/baselines/epipolar_rotation.h"
#endif

namespace {
using Clock = std::chrono::steady_clock;
using gasp::msSince;
}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"gasp-pairs: relative-pose benchmark over frame pairs of a TUM RGB-D folder (the GASP paper's protocol), "
               "GASP beside the feature baselines"};
  gasp::tools::ParamsOptions params_options;
  gasp::SlamParams all_params;
  if (!params_options.preload(argc, argv, all_params)) return 1;
  gasp::PairParams& base = all_params.odometry.pair;  // GASP's pipeline: the params file's sections segment to retry
  std::string tum_dir, intrinsics_arg, csv_path, pairs_csv_path, picture_prefix = "pair_";
  std::vector<std::size_t> skips{10, 20, 30, 40};
  std::vector<std::string> methods{"gasp"};
  std::vector<std::size_t> picture_pair;
  std::size_t starts_every = 10, max_pairs = 0;
  app.add_option("--tum", tum_dir, "TUM RGB-D folder (required)");
  app.add_option("--skips", skips, "frame skips (in depth.txt order)")
      ->delimiter(',')
      ->capture_default_str()
      ->check(gasp::tools::atLeast(1));
  app.add_option("--starts-every", starts_every, "start frames 0, N, 2N, ...")->capture_default_str()->check(gasp::tools::atLeast(1));
  app.add_option("--method", methods,
                 "gasp (full pipeline), gasp-norefine (RANSAC only); baselines (when built): fpfh, shot, cshot, sift, dsift, "
                 "gicp (PCL's GICP from the identity), gasp-gicp (GICP from GASP's pose)")
      ->delimiter(',')->check(CLI::IsMember(gasp::pairs::knownMethods()))->capture_default_str();
  bool no_undistort = false;
  app.add_flag("--no-undistort", no_undistort, "resample depth (and rgb) to the pinhole camera when the intrinsics have lens distortion (fr1, fr2: default); this flag uses the images as stored");
  app.add_option("--intrinsics", intrinsics_arg, "fr1|fr2|fr3|ros or an intrinsics file (default: the folder's)");
  double depth_scale = gasp::kTumDepthUnitsPerMetre;
  app.add_option("--depth-scale", depth_scale, "raw depth units per metre (TUM: 5000; a calibrated depth scale divides it)")
      ->capture_default_str()
      ->check(gasp::tools::above(0));
  app.add_option("--csv", csv_path, "write the table as CSV (rows with scored pairs only)")->check(gasp::tools::nonEmpty());
  app.add_option("--pairs-csv", pairs_csv_path, "write one line per pair and method")->check(gasp::tools::nonEmpty());
  app.add_option("--max-pairs", max_pairs, "at most this many pairs per skip (0 = all)")->check(gasp::tools::atLeast(0));
  app.add_option("--picture", picture_pair, "also draw the pair I,J for every method (not scored)")
      ->delimiter(',')->expected(2)->check(gasp::tools::atLeast(0));
  app.add_option("--picture-prefix", picture_prefix, "pictures go to PREFIX<method>.<format>")->capture_default_str();
  std::string picture_format = "png";
  app.add_option("--picture-format", picture_format, "png or jpg (smaller files)")
      ->check(CLI::IsMember({"png", "jpg"}))->capture_default_str();
  bool pictures_only = false, setup_picture_free = false;
  app.add_flag("--pictures-only", pictures_only, "draw the --picture pair and stop (no benchmark)");
  app.add_flag("--picture-free", setup_picture_free,
               "GASP's pictures show the free associations (before any pose) instead of the verified ones");
  bool polish_reference = false;  // --polish-reference (with the baselines only)
  bool rgb_rotation_check = false;  // --rgb-rotation-check (with the baselines only)
#ifdef GASP_HAVE_BASELINES
  gasp::baselines::EpipolarParams epipolar;
  gasp::baselines::BaselineParams baseline;
  app.add_option("--ratio", baseline.matching.ratio, "baselines: Lowe's ratio test threshold")->capture_default_str()->check(gasp::tools::aboveAndAtMost(0, 1));
  app.add_flag("!--no-mutual-matches", baseline.matching.mutual, "baselines: no mutual check of descriptor matches");
  app.add_option("--min-keypoints", baseline.point.min_keypoints, "fpfh/shot/cshot: keypoints per view")->capture_default_str()->check(gasp::tools::atLeast(1));
  app.add_flag("--polish-reference", polish_reference,
               "--pairs-csv: also run PCL's GICP from the reference pose and from each estimate (an independent "
               "check of the reference; columns ref_icp_*, est_vs_ref_icp_*, est_icp_*)");
  app.add_flag("--rgb-rotation-check", rgb_rotation_check,
               "--pairs-csv: also estimate each pair's rotation from the colour images alone (SIFT, essential "
               "matrix) and compare it with the reference's and each estimate's (columns rgb_*; pairs with rgb)");
  std::string rgb_intrinsics_arg;
  app.add_option("--rgb-intrinsics", rgb_intrinsics_arg,
                 "--rgb-rotation-check: the colour camera's focal lengths and centre (fr1|fr2|fr3|ros or a file; its "
                 "lens coefficients are ignored, the images are already undistorted); default: the folder's, which "
                 "is wrong when --intrinsics carries a depth calibration");
  app.add_option("--rgb-contrast", epipolar.contrast_threshold,
                 "--rgb-rotation-check: SIFT contrast threshold (lower finds more features in flat images)")
      ->capture_default_str()
      ->check(gasp::tools::above(0));
#endif
  gasp::DeskewParams deskew;
  auto* rolling_shutter_option = app.add_option("--rolling-shutter", deskew.readout_s,
                 "GASP: deskew each depth image for a rolling shutter with this readout time [s] (first row to last; "
                 "negative: bottom-up; TUM's Kinect: 0.03), with the velocity from --twist-from")
      ->capture_default_str();
  std::string twist_from = "neighbours";
  app.add_option("--twist-from", twist_from,
                 "velocity for --rolling-shutter: neighbours (GASP's pose between frames i-1 and i+1) or truth (the "
                 "reference's, at the depth stamp + --gt-offset; a diagnostic)")
      ->check(CLI::IsMember({"neighbours", "truth"}))
      ->needs(rolling_shutter_option)
      ->capture_default_str();
  int roll_target = 0;
  app.add_option("--roll-target", roll_target,
                 "GASP: turn each pair's target view (frame I+skip) by DEG clockwise (0, 90, 180, 270) before "
                 "segmenting it, and score against the reference rolled the same way: the camera rolled about its "
                 "optical axis, on real data (gasp and gasp-norefine only; --pairs-csv's motion columns include the roll)")
      ->capture_default_str()
      ->check(CLI::IsMember({0, 90, 180, 270}));
  bool reverse = false;
  app.add_flag("--reverse", reverse,
               "register each pair the other way round: target frame I, source frame I+skip (the direction "
               "gasp-odometry registers a frame to its keyframe), scored against the inverse reference; with "
               "--roll-target frame I is the one turned");
  double gt_offset = 0.0;
  app.add_option("--gt-offset", gt_offset,
                 "look ground truth up at depth timestamp + OFFSET [s] (nearest within 0.02 s; TUM fr1 depth lags "
                 "the motion capture: -0.03 fits best, docs/pipeline.md)")
      ->capture_default_str()
      ->check(gasp::tools::within(-60, 60));
  std::vector<double> gt_frame_rotation_deg;
  app.add_option("--gt-frame-rotation", gt_frame_rotation_deg,
                 "RX,RY,RZ [deg]: take the reference's camera frame as turned by exp(r) against the depth camera's "
                 "and turn it back before scoring (ground truth of the pairs, the rgb check and --polish-reference; "
                 "a diagnostic, docs/pipeline.md 'A constant frame rotation')")
      ->expected(3)
      ->delimiter(',');
  params_options.add(app);
  try {
    app.parse(argc, argv);
    for (const double v : gt_frame_rotation_deg)
      if (!(std::abs(v) <= 360.0))
        throw CLI::ValidationError("--gt-frame-rotation must be three angles in degrees, each within +-360");
    if (pictures_only && picture_pair.empty()) throw CLI::ValidationError("--pictures-only needs --picture I,J");
    if (!std::isfinite(deskew.readout_s) || std::abs(deskew.readout_s) > 1.0)
      throw CLI::ValidationError("--rolling-shutter must be a finite time of at most 1 s (either sign)");
    if (polish_reference && pairs_csv_path.empty())
      throw CLI::ValidationError("--polish-reference writes its columns to the --pairs-csv file: give --pairs-csv");
    if (roll_target != 0) {
      for (const auto& m : methods)
        if (m != "gasp" && m != "gasp-norefine")
          throw CLI::ValidationError("--roll-target: GASP's methods only (gasp, gasp-norefine), not " + m);
      if (polish_reference || rgb_rotation_check)
        throw CLI::ValidationError("--roll-target: not with --polish-reference or --rgb-rotation-check");
    }
    if (reverse && rgb_rotation_check) throw CLI::ValidationError("--reverse: not with --rgb-rotation-check");
    if (rgb_rotation_check && pairs_csv_path.empty())
      throw CLI::ValidationError("--rgb-rotation-check writes its columns to the --pairs-csv file: give --pairs-csv");
  } catch (const CLI::ParseError& e) {
    return gasp::tools::usageExit(app, e);  // --help: 0; any usage error: 2
  }
  if (const int code = params_options.printIfAsked(all_params); code >= 0) return code;
  if (tum_dir.empty()) {
    std::cerr << "error: --tum is required\nRun with --help for more information.\n";
    return 2;
  }
  // Each method once, in the order given.
  {
    std::vector<std::string> unique;
    for (const auto& m : methods)
      if (std::find(unique.begin(), unique.end(), m) == unique.end()) unique.push_back(m);
    methods = unique;
  }
  // Every output, the pictures included, is checked before the work.
  std::vector<std::pair<std::string, std::string>> output_paths{{"--csv", csv_path}, {"--pairs-csv", pairs_csv_path}};
  if (!picture_pair.empty())
    for (const auto& method : methods)
      if (method != "gicp") output_paths.emplace_back("--picture-prefix", picture_prefix + method + "." + picture_format);
  std::optional<gasp::tools::RunOutputs> outputs;
  try {
    outputs.emplace(output_paths, gasp::tools::tumFolderInputs(tum_dir));  // before the benchmark, not after it
  } catch (const gasp::Error& e) {
    std::cerr << "error: " << gasp::exceptionMessage(e) << '\n';
    return 1;
  }
  bool progress_line_open = false;  // an error then starts on a line of its own
  try {
    gasp::pairs::MethodSetup setup;
#ifdef GASP_HAVE_BASELINES
    baseline.pose.ransac.min_inliers = base.hypothesise.pose.ransac.min_inliers;  // the same consensus rule for all
    baseline.visibility = base.certify.visibility;  // and the same free-space check
    gasp::baselines::validate(baseline);
    gasp::baselines::validate(epipolar);
    setup.baseline = baseline;
#endif
    setup.gasp = base;
    setup.roll_target_deg = roll_target;
    setup.picture_free = setup_picture_free;
    gasp::TumDataset::Options opt;
    if (!intrinsics_arg.empty()) opt.intrinsics = gasp::CameraIntrinsics::fromPresetOrFile(intrinsics_arg);
    opt.undistort = !no_undistort;
    opt.depth_units_per_metre = depth_scale;
    const auto ds = gasp::TumDataset::open(tum_dir, opt);
    // On stderr: stdout is the table.
    gasp::tools::reportIntrinsics(stderr, ds.intrinsicsSummary(), ds.intrinsicsWarning());
    Eigen::Vector3d frame_rotation = Eigen::Vector3d::Zero();
    if (!gt_frame_rotation_deg.empty())
      frame_rotation = Eigen::Vector3d(gt_frame_rotation_deg[0], gt_frame_rotation_deg[1], gt_frame_rotation_deg[2]) *
                       (M_PI / 180.0);
    const gasp::pairs::PairReference reference(ds, gt_offset, frame_rotation, roll_target);
    auto hasRgb = [&](std::size_t i) { return ds.frame(i).rgb_path.has_value(); };

    std::optional<gasp::pairs::DeskewFilter> deskew_filter;
    gasp::pairs::FrameCache::DepthFilter filter;
    if (deskew.readout_s != 0.0) {
      deskew_filter.emplace(ds, deskew,
                            twist_from == "truth" ? gasp::pairs::DeskewFilter::TwistFrom::kTruth
                                                  : gasp::pairs::DeskewFilter::TwistFrom::kNeighbours,
                            base, gt_offset);
      filter = [&](std::size_t i, const cv::Mat& depth) { return (*deskew_filter)(i, depth); };
    }
    gasp::pairs::FrameCache cache(ds, filter);

    // Pictures of one pair first (not scored).
    if (!picture_pair.empty()) {
      const std::size_t i = picture_pair[0], j = picture_pair[1];
      if (i >= ds.size() || j >= ds.size()) throw gasp::Error("--picture: frame index beyond the folder's frames");
      const std::optional<gasp::Isometry3> T_gt = reference.pair(i, j);
      for (const auto& method : methods) {
        if (gasp::pairs::needsColour(method) && (!hasRgb(i) || !hasRgb(j))) {
          std::printf("picture %s: n/a (no rgb)\n", method.c_str());
          continue;
        }
        if (method == "gicp") {  // no associations to draw
          std::printf("picture %s: n/a (GICP has no associations)\n", method.c_str());
          continue;
        }
        gasp::pairs::Picture pic;
        const auto run = gasp::pairs::runMethod(method, i, j, cache, setup, &pic, T_gt);
        const std::string path = picture_prefix + method + "." + picture_format;
        gasp::writeImage(outputs->at("--picture-prefix", path), pic.image, "picture");
        std::printf("picture %s: %s, %zu associations/matches, %zu correct by ground truth", method.c_str(),
                    path.c_str(), pic.shown, pic.correct);
        if (run.estimated && T_gt) {
          gasp::eval::PairOutcome o;
          gasp::eval::scorePose(run.T_target_source, *T_gt, o);
          std::printf(", pose error %.4f m %.3f deg\n", o.t_err_m, o.r_err_deg);
        } else {
          std::printf(", %s\n", run.estimated ? "estimate (no ground truth)" : ("no estimate: " + run.reason).c_str());
        }
      }
      cache.dropBefore(ds.size());
      if (pictures_only) return 0;
    }

    // All pairs, visited by start frame so that each frame is described once while it is in use.
    gasp::pairs::PairsTally tally;
    std::vector<std::pair<std::size_t, std::size_t>> all;  // (from, skip)
    for (const std::size_t skip : skips) {
      auto pairs = gasp::eval::makePairs(ds.size(), skip, starts_every);
      // Only pairs where both frames have ground truth can be scored.
      pairs.erase(std::remove_if(pairs.begin(), pairs.end(),
                                 [&](const auto& p) { return !reference.frame(p.first) || !reference.frame(p.second); }),
                  pairs.end());
      if (max_pairs > 0 && pairs.size() > max_pairs) pairs.resize(max_pairs);
      tally.pairs_per_skip[skip] = pairs.size();
      for (const auto& p : pairs) all.emplace_back(p.first, skip);
    }
    std::stable_sort(all.begin(), all.end(), [](const auto& a, const auto& b) { return a.first < b.first; });

    gasp::OutputFile* pairs_csv = outputs->find("--pairs-csv");
    if (pairs_csv) pairs_csv->stream() << gasp::pairs::pairsCsvHeader() << '\n';
    // The colour camera of the (undistorted) rgb images: the folder's, or --rgb-intrinsics' K.
    gasp::CameraIntrinsics rgb_camera = ds.intrinsics();
#ifdef GASP_HAVE_BASELINES
    if (!rgb_intrinsics_arg.empty()) {
      rgb_camera = gasp::CameraIntrinsics::fromPresetOrFile(rgb_intrinsics_arg);
      rgb_camera.distortion.fill(0.0);
      if (rgb_camera.width != ds.intrinsics().width || rgb_camera.height != ds.intrinsics().height)
        throw gasp::Error("--rgb-intrinsics: " + std::to_string(rgb_camera.width) + "x" +
                          std::to_string(rgb_camera.height) + ", the images are " +
                          std::to_string(ds.intrinsics().width) + "x" + std::to_string(ds.intrinsics().height));
    }
#endif
    const auto bench_t0 = Clock::now();
    std::size_t done = 0;
    for (const auto& [i, skip] : all) {
      cache.dropBefore(i);
      const std::size_t j = i + skip;
      // Source a, target b: frame i onto frame j, or with --reverse frame j onto frame i.
      const std::size_t a = reverse ? j : i, b = reverse ? i : j;
      gasp::pairs::PairsCsvChecks checks;
      checks.T_gt = *reference.pair(a, b);
      // The reference polished by GICP (once per pair): how far the depth pulls it, and where to.
      if (polish_reference) checks.T_ref_icp = gasp::pairs::polishWithGicp(cache, a, b, base.segment, checks.T_gt);
#ifdef GASP_HAVE_BASELINES
      if (rgb_rotation_check)
        checks.rgb = gasp::pairs::checkRgbRotation(ds, cache, reference, i, j, rgb_camera, epipolar);
#endif
      for (const auto& method : methods) {
        if (gasp::pairs::needsColour(method) && (!hasRgb(i) || !hasRgb(j))) {
          ++tally.no_rgb[{skip, method}];
          continue;
        }
        const auto run = gasp::pairs::runMethod(method, a, b, cache, setup, nullptr, checks.T_gt, checks.T_ref_icp);
        gasp::eval::PairOutcome o;
        o.skip = skip;
        o.from = i;
        o.to = j;
        o.ms = run.ms;
        o.estimated = run.estimated;
        o.reason = run.reason;
        if (run.estimated) gasp::eval::scorePose(run.T_target_source, checks.T_gt, o);
        for (const auto& [stage, ms] : run.stage_ms) tally.stage_ms[method][stage].push_back(ms);
        tally.by_method[method].push_back(o);
        if (pairs_csv) {
          checks.T_est_icp = run.estimated && polish_reference
                                 ? gasp::pairs::polishWithGicp(cache, a, b, base.segment, run.T_target_source)
                                 : std::nullopt;
          pairs_csv->stream() << gasp::pairs::pairsCsvRow(o, method, run, checks) << '\n';
        }
      }
      ++done;
      std::fprintf(stderr, "\rpair %zu/%zu (%.0f s)", done, all.size(), msSince(bench_t0) / 1000.0);
      std::fflush(stderr);
      progress_line_open = true;
    }
    if (!all.empty()) std::fprintf(stderr, "\n");
    progress_line_open = false;

    std::size_t total_pairs = 0;
    const auto rows = gasp::pairs::printPairsTable(skips, methods, tally, total_pairs);
    gasp::pairs::printStageTimes(methods, tally);
    if (reverse) std::printf("direction: reversed (each pair's frame I+skip registered onto frame I)\n");
    if (roll_target != 0)
      std::printf("roll_target: %d deg clockwise (each pair's target view turned; scored against the rolled reference)\n",
                  roll_target);
    if (deskew_filter) {
      std::printf("rolling_shutter: readout %.4f s, velocity from %s, %zu of %zu frames deskewed", deskew.readout_s,
                  twist_from.c_str(), deskew_filter->framesDeskewed(), deskew_filter->framesSeen());
      if (!deskew_filter->msPerFrame().empty())
        std::printf(", median %.1f ms per frame for the neighbours and the deskew (not in the pair times)",
                    gasp::pairs::median(deskew_filter->msPerFrame()));
      std::printf("\n");
    }
    std::printf("wall_time_s: %.1f\n", msSince(bench_t0) / 1000.0);
    if (pairs_csv) pairs_csv->commit();
    if (auto* csv = outputs->find("--csv")) {
      csv->stream() << gasp::eval::csvHeader() << '\n';
      for (const auto& s : rows) csv->stream() << gasp::eval::csvRow(s) << '\n';
      csv->commit();
    }
    if (total_pairs == 0 && picture_pair.empty()) {
      if (ds.size() < 2)
        std::fprintf(stderr, "no pair: the folder has %zu depth frame%s\n", ds.size(), ds.size() == 1 ? "" : "s");
      else
        std::fprintf(stderr, "no pair with ground truth for both frames\n");
      return 4;
    }
  } catch (const std::exception& e) {  // gasp::Error, or e.g. a cv::Exception from a library
    std::cerr << (progress_line_open ? "\n" : "") << "error: " << gasp::exceptionMessage(e) << '\n';
    return 1;
  }
  return 0;
}
