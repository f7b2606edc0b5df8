// gasp-pairs: the paper's pair benchmark on a TUM folder, GASP beside the feature baselines.
//   gasp-pairs --tum DIR [--skips 10,20,30,40] [--starts-every N]
//              [--method gasp,gasp-norefine,fpfh,shot,cshot,sift,dsift,gicp,gasp-gicp] [--csv OUT.csv]
//              [--pairs-csv OUT_pairs.csv] [--max-pairs N] [--picture I,J [--picture-prefix P] [--picture-format png|jpg] [--pictures-only]]
// Pairs (i, i + skip) from start frames 0, N, 2N, ... (indices in depth.txt order); for each pair
// and method a relative pose is estimated and compared with ground truth. Prints one table row per
// skip and method (definitions in gasp/eval/pair_protocol.h and docs/evaluation.md); progress goes
// to stderr. The baselines (fpfh, shot, cshot, sift, dsift; gasp/baselines/) and PCL's GICP from
// the identity (gicp) or from GASP's pose (gasp-gicp) exist when the build has GASP_BUILD_BASELINES. Colour methods (cshot, sift, dsift) are not run on pairs where a frame
// has no rgb: those rows say "n/a (no rgb)" and count the pairs left out.
// Time per pair = description of both views (segmentation for GASP; measured once per frame and
// charged to every pair using it) + association or matching + pose stages; image loading excluded.
// --roll-target DEG turns each pair's target image by a quarter or half turn (the camera rolled
// about its optical axis; GASP's methods only) and scores against the reference rolled alike.
// Exit codes: 0 done, 1 bad input, 2 usage error, 4 no pair with ground truth.
#include <CLI/CLI.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <optional>
#include <set>

#include "gasp/core/camera_roll.h"
#include "gasp/core/stopwatch.h"
#include "gasp/association/association_picture.h"
#include "gasp/association/association_quality.h"
#include "gasp/core/error.h"
#include "gasp/core/image_file.h"
#include "gasp/core/tum_dataset.h"
#include "gasp/core/tum_trajectory.h"
#include "gasp/eval/pair_protocol.h"
#include "gasp/eval/pose_consistency.h"
#include "gasp/pipeline/pair_registration.h"
#include "gasp/pipeline/rolling_shutter_deskew.h"
#include "gasp/pipeline/visibility_check.h"
#include "cli.h"
#ifdef GASP_HAVE_BASELINES
#include "gasp/baselines/baseline_registration.h"
#include "gasp/baselines/epipolar_rotation.h"
#include "gasp/baselines/icp_polish.h"
#include "gasp/baselines/match_picture.h"
#endif

namespace {

using Clock = std::chrono::steady_clock;
using gasp::msSince;


double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/// GASP's pipeline runs (gasp-gicp: then PCL's GICP from its pose).
bool isGasp(const std::string& method) {
  return method == "gasp" || method == "gasp-norefine" || method == "gasp-gicp";
}

std::vector<std::string> knownMethods() {
  std::vector<std::string> m{"gasp", "gasp-norefine"};
#ifdef GASP_HAVE_BASELINES
  for (auto b : gasp::baselines::allMethods()) m.push_back(gasp::baselines::methodName(b));
  m.push_back("gicp");       // PCL's GICP from the identity: ICP without a start
  m.push_back("gasp-gicp");  // GICP started from GASP's pose: ICP with GASP's start
#endif
  return m;
}

/// One pair, one method: the outcome plus what the pictures need.
struct MethodRun {
  bool estimated = false;
  gasp::Isometry3 T_target_source = gasp::Isometry3::Identity();
  std::string reason;
  double ms = 0;
  std::size_t associations = 0;
  int inliers = 0;
  double violation_ratio = 0;
  int consistent = 0, occluded = 0, violations = 0;  ///< visibility check samples, both directions
  double occluded_ratio = 0;                          ///< visibility check, the worse direction
  int one_way = 0;          ///< GASP: the pose came from the one-way fallback
  int guided_support = -1;  ///< GASP: guided associations under the pose (-1: not reached)
  bool finer_scale = false; ///< GASP: the estimate came from the finer-scale retry
  bool slide_moved = false; ///< GASP: the slide scan moved the pose (slide_scan.h)
  int dense_terms = 0;      ///< GASP: terms of the last dense round (0: no dense rounds ran)
  int dense_rounds = 0;     ///< GASP: dense rounds run for the final pose (0: none)
  double dense_last_step_m = -1.0;  ///< GASP: RMS motion of the source patches in the last dense round (-1: none)
  int dense_shortened = 0;  ///< GASP: dense steps the line search shortened
  bool dense_stopped = false;  ///< GASP: the line search ended the dense rounds
  /// GASP with an estimate and ground truth: the error's NEES under the edge information (PairResult)
  /// and its translation and rotation parts (pose_consistency.h; chi-square with 6, 3 and 3
  /// degrees of freedom if the information were right).
  std::optional<gasp::eval::NeesParts> nees;
  std::optional<double> nees_refinement;  ///< the same under the refinement's own information
  /// GASP with ground truth: free and verified associations scored (association_quality.h).
  std::optional<gasp::AssociationQuality> free_quality, verified_quality;
  /// The verified associations scored against the GICP-polished reference (--polish-reference).
  std::optional<gasp::AssociationQuality> verified_quality_polished;
  /// GASP with ground truth: how well each pose explains the depth (depthAgreement, every 4th pixel), the estimate's
  /// and the ground truth's, so a disagreement between them can be told apart.
  std::optional<double> agreement_estimate, agreement_truth;
  std::map<std::string, double> stage_ms;
};

/// Views and descriptions per frame, kept while later pairs may use them (pairs are visited by
/// start frame, so frames before the current start are dropped).
class FrameCache {
 public:
  /// Applied to each depth image (metres) before GASP's segmentation; none: the image as loaded.
  using DepthFilter = std::function<cv::Mat(std::size_t, const cv::Mat&)>;
  explicit FrameCache(const gasp::TumDataset& ds, DepthFilter filter = {}) : ds_(ds), filter_(std::move(filter)) {}

  struct GaspView {
    gasp::DepthView view;
    double ms = 0;
  };
  /// Frame i segmented; turned clockwise by `turn_deg` first (camera_roll.h), a view of its own.
  const GaspView& gaspView(std::size_t i, const gasp::SuperpixelParams& params, int turn_deg = 0) {
    auto it = gasp_.find({i, turn_deg});
    if (it != gasp_.end()) return it->second;
    cv::Mat depth = filter_ ? filter_(i, ds_.loadDepth(i)) : ds_.loadDepth(i);
    gasp::CameraIntrinsics K = ds_.intrinsics();
    if (turn_deg != 0) {
      depth = gasp::turnImage(depth, turn_deg);
      K = gasp::turnIntrinsics(K, turn_deg);
    }
    const auto t0 = Clock::now();
    GaspView v{gasp::makeDepthView(depth, K, params), 0.0};
    v.ms = msSince(t0);
    return gasp_.emplace(std::make_pair(i, turn_deg), std::move(v)).first->second;
  }

#ifdef GASP_HAVE_BASELINES
  const gasp::baselines::RgbdImage& rgbd(std::size_t i) {
    auto it = rgbd_.find(i);
    if (it != rgbd_.end()) return it->second;
    return rgbd_.emplace(i, gasp::baselines::RgbdImage{ds_.loadDepth(i), ds_.loadRgb(i), ds_.intrinsics()})
        .first->second;
  }
  const gasp::baselines::DescribedKeypoints& described(std::size_t i, gasp::baselines::BaselineMethod m,
                                                       const gasp::baselines::BaselineParams& params) {
    const auto key = std::make_pair(i, static_cast<int>(m));
    auto it = described_.find(key);
    if (it != described_.end()) return it->second;
    const auto& view = rgbd(i);
    gasp::baselines::DescribedKeypoints k;
    switch (m) {
      case gasp::baselines::BaselineMethod::kFpfh:
        k = describePointFeatures(view, gasp::baselines::PointFeatureType::kFpfh, params.point);
        break;
      case gasp::baselines::BaselineMethod::kShot:
        k = describePointFeatures(view, gasp::baselines::PointFeatureType::kShot, params.point);
        break;
      case gasp::baselines::BaselineMethod::kColourShot:
        k = describePointFeatures(view, gasp::baselines::PointFeatureType::kColourShot, params.point);
        break;
      case gasp::baselines::BaselineMethod::kSift: k = describeSift(view, params.sift); break;
      case gasp::baselines::BaselineMethod::kDenseSift: k = describeDenseSift(view, params.dense_sift); break;
    }
    return described_.emplace(key, std::move(k)).first->second;
  }
#endif

  void dropBefore(std::size_t first) {
    gasp_.erase(gasp_.begin(), gasp_.lower_bound(std::make_pair(first, -1)));
#ifdef GASP_HAVE_BASELINES
    rgbd_.erase(rgbd_.begin(), rgbd_.lower_bound(first));
    described_.erase(described_.begin(), described_.lower_bound(std::make_pair(first, -1)));
#endif
  }

 private:
  const gasp::TumDataset& ds_;
  DepthFilter filter_;
  std::map<std::pair<std::size_t, int>, GaspView> gasp_;  ///< (frame, turn) -> view
#ifdef GASP_HAVE_BASELINES
  std::map<std::size_t, gasp::baselines::RgbdImage> rgbd_;
  std::map<std::pair<std::size_t, int>, gasp::baselines::DescribedKeypoints> described_;
#endif
};

/// The picture of one method on one pair: GASP's association picture (patches in shared
/// colours), or the baselines' keypoint matches over the rgb images. Lines are green where the
/// ground truth says correct (GASP: the same surface, association_quality.h; keypoints: the
/// mapped source keypoint within 5 cm of its partner), red where wrong.
struct Picture {
  cv::Mat image;
  std::size_t shown = 0, correct = 0;
};

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"gasp-pairs: relative-pose benchmark over frame pairs of a TUM RGB-D folder (the GASP paper's protocol), "
               "GASP beside the feature baselines"};
  std::string tum_dir, intrinsics_arg, csv_path, pairs_csv_path, picture_prefix = "pair_";
  std::vector<std::size_t> skips{10, 20, 30, 40};
  std::vector<std::string> methods{"gasp"};
  std::vector<std::size_t> picture_pair;
  std::size_t starts_every = 10, max_pairs = 0;
  app.add_option("--tum", tum_dir, "TUM RGB-D folder")->required();
  app.add_option("--skips", skips, "frame skips (in depth.txt order)")
      ->delimiter(',')
      ->capture_default_str()
      ->check(gasp::tools::atLeast(1));
  app.add_option("--starts-every", starts_every, "start frames 0, N, 2N, ...")->capture_default_str()->check(gasp::tools::atLeast(1));
  app.add_option("--method", methods,
                 "gasp (full pipeline), gasp-norefine (RANSAC only); baselines (when built): fpfh, shot, cshot, sift, dsift, "
                 "gicp (PCL's GICP from the identity), gasp-gicp (GICP from GASP's pose)")
      ->delimiter(',')->check(CLI::IsMember(knownMethods()))->capture_default_str();
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
  bool pictures_only = false;
  app.add_flag("--pictures-only", pictures_only, "draw the --picture pair and stop (no benchmark)");
  gasp::PairParams base;
  app.add_option("--k", base.association.feature_sets.neighbourhood.k, "association neighbourhood size (0 = full view)")->capture_default_str()->check(gasp::tools::atLeast(0));
  double area_cm2 = base.superpixels.target_patch_area_m2 * 1e4;
  app.add_option("--area-cm2", area_cm2, "GASP: target patch area [cm^2]")->capture_default_str()->check(gasp::tools::above(0));
  app.add_flag("--step-borders", base.superpixels.step_borders, "GASP: segment with the step borders (SuperpixelParams::step_borders; off by default)");
  app.add_option("--candidates", base.association.candidates, "KD-tree candidates per patch (C)")->capture_default_str()->check(gasp::tools::atLeast(1));
  app.add_option("--lambda", base.association.lambda, "gating on the normalised edit distance")->capture_default_str()->check(gasp::tools::within(0, 1));
  app.add_option("--distinctiveness", base.association.distinctiveness_ratio,
                 "ratio test: keep a best partner only when its D_hat < R x the second best (1 = off)")
      ->capture_default_str()
      ->check(gasp::tools::above(0))
      ->check(gasp::tools::within(0, 1));
  app.add_flag("!--no-mutual", base.association.mutual_check, "keep one-way best partners too (no mutual check)");
  app.add_option("--min-inliers", base.pose.ransac.min_inliers, "RANSAC: fewer inliers give no estimate (all methods)")->capture_default_str()->check(gasp::tools::atLeast(3));
  app.add_option("--one-way-max-violation", base.one_way_max_violation_ratio,
                 "GASP: visibility check violation limit for poses from the one-way fallback")->capture_default_str()->check(gasp::tools::within(0, 1));
  app.add_option("--max-occluded", base.visibility.max_occluded_ratio,
                 "visibility check: limit on the share of samples behind the other view's surfaces (all methods)")->capture_default_str()->check(gasp::tools::within(0, 1));
  app.add_option("--retry-area-factor", base.retry_area_factor,
                 "GASP: when no estimate is found, segment again with this times the patch area and retry, mutual associations only (0 = never, else in [0.01, 1))")
      ->capture_default_str()
      ->check(gasp::tools::zeroOrWithinHalfOpen(0.01, 1));
  app.add_flag("!--no-slide-scan", base.slide_scan.enabled,
               "GASP: no slide scan of poses whose patch problem was degenerate (docs/pipeline.md, \"Slide scan\")");
  app.add_flag("!--no-edge-terms", base.edge_terms, "GASP: no point-to-line terms along occluding edges in the dense rounds");
  app.add_option("--edge-weight", base.edges.weight, "GASP: weight of an edge term (0 = edge terms weightless)")->capture_default_str()->check(gasp::tools::atLeast(0));
  app.add_option("--wide-edge-gates", base.wide_edge_gate_factor,
                 "GASP: second refinement, when few edge points are paired, with edge gates this many times wider (0 = none, else >= 1)")->capture_default_str()->check(gasp::tools::zeroOrAtLeast(1));
  app.add_option("--edge-step", base.edges.pixel_step, "GASP: one source edge pixel per (N/2)^2 image block")->capture_default_str()->check(gasp::tools::above(0));
  app.add_option("--dense-rounds", base.dense_rounds, "dense projective refinement rounds (0 = none)")->capture_default_str()->check(gasp::tools::atLeast(0));
  app.add_option("--dense-max-rounds", base.dense_max_rounds,
                 "at most this many dense rounds in all: after --dense-rounds, more at the last gate until the pose stops moving (<= --dense-rounds: exactly --dense-rounds)")
      ->capture_default_str()
      ->check(gasp::tools::atLeast(0));
  app.add_option("--dense-extrapolation", base.dense_extrapolation_max,
                 "after two dense rounds at the last gate that move the pose the same way, start the next at most this many steps ahead (0 = never)")
      ->capture_default_str()
      ->check(gasp::tools::atLeast(0));
  app.add_flag("!--no-dense-line-search", base.dense_line_search,
               "GASP: no line search at the last dense gate (a longer step than the round before is kept even when it scores worse; docs/pipeline.md, \"Line search at the last gate\")");
  app.add_option("--pixel-step", base.projective.pixel_step, "dense terms: every N-th pixel")->capture_default_str()->check(gasp::tools::atLeast(1));
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
  double gt_offset = 0.0;
  app.add_option("--gt-offset", gt_offset,
                 "look ground truth up at depth timestamp + OFFSET [s] (nearest within 0.02 s; TUM fr1 depth lags "
                 "the motion capture: -0.03 fits best, docs/pipeline.md)")
      ->capture_default_str()
      ->check(gasp::tools::within(-60, 60));
  std::vector<double> model_error;
  app.add_option("--model-error", model_error,
                 "T_M,R_DEG: GASP's model error per axis, added to the claimed pose's covariance for the edge information "
                 "(default 0.01,0.75; the nees columns of --pairs-csv are against it, docs/pipeline.md)")
      ->expected(2)
      ->delimiter(',');
  std::vector<double> gt_frame_rotation_deg;
  app.add_option("--gt-frame-rotation", gt_frame_rotation_deg,
                 "RX,RY,RZ [deg]: take the reference's camera frame as turned by exp(r) against the depth camera's "
                 "and turn it back before scoring (ground truth of the pairs, the rgb check and --polish-reference; "
                 "a diagnostic, docs/pipeline.md 'A constant frame rotation')")
      ->expected(3)
      ->delimiter(',');
  try {
    app.parse(argc, argv);
    for (const double v : gt_frame_rotation_deg)
      if (!(std::abs(v) <= 360.0))
        throw CLI::ValidationError("--gt-frame-rotation must be three angles in degrees, each within +-360");
    if (!model_error.empty()) {
      base.model_error = {model_error[0], model_error[1]};
      try {
        gasp::validate(base.model_error);
      } catch (const gasp::Error& e) {
        throw CLI::ValidationError(std::string("--model-error: ") + e.what());
      }
    }
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
    if (rgb_rotation_check && pairs_csv_path.empty())
      throw CLI::ValidationError("--rgb-rotation-check writes its columns to the --pairs-csv file: give --pairs-csv");
  } catch (const CLI::ParseError& e) {
    return gasp::tools::usageExit(app, e);  // --help: 0; any usage error: 2
  }
  // Each method once, in the order given.
  {
    std::vector<std::string> unique;
    for (const auto& m : methods)
      if (std::find(unique.begin(), unique.end(), m) == unique.end()) unique.push_back(m);
    methods = unique;
  }
  if (const std::string missing = gasp::tools::missingOutputFolder({{"--csv", csv_path}, {"--pairs-csv", pairs_csv_path}});
      !missing.empty()) {
    std::cerr << "error: " << missing << '\n';  // before the benchmark, not after it
    return 1;
  }
  try {
    base.superpixels.target_patch_area_m2 = area_cm2 * 1e-4;
#ifdef GASP_HAVE_BASELINES
    baseline.pose.ransac.min_inliers = base.pose.ransac.min_inliers;  // the same consensus rule for all
    baseline.visibility = base.visibility;  // and the same free-space check
    gasp::baselines::validate(baseline);
    gasp::baselines::validate(epipolar);
#endif
    gasp::TumDataset::Options opt;
    if (!intrinsics_arg.empty()) opt.intrinsics = gasp::CameraIntrinsics::fromPresetOrFile(intrinsics_arg);
    opt.undistort = !no_undistort;
    opt.depth_units_per_metre = depth_scale;
    const auto ds = gasp::TumDataset::open(tum_dir, opt);
    // On stderr: stdout is the table.
    gasp::tools::reportIntrinsics(stderr, ds.intrinsicsSummary(), ds.intrinsicsWarning());
    // Ground truth of frame i: the frame's own association (offset 0) or a look-up at t + offset.
    // --gt-frame-rotation: the reference's camera frame is the depth camera's turned by Q, so the
    // depth camera's pose is T_world_ref * Q^-1.
    gasp::Isometry3 Q_inv = gasp::Isometry3::Identity();
    if (!gt_frame_rotation_deg.empty()) {
      const Eigen::Vector3d r = Eigen::Vector3d(gt_frame_rotation_deg[0], gt_frame_rotation_deg[1],
                                                gt_frame_rotation_deg[2]) * (M_PI / 180.0);
      if (r.norm() > 0) Q_inv.linear() = Eigen::AngleAxisd(r.norm(), r.normalized()).toRotationMatrix().transpose();
    }
    auto turnedBack = [&](std::optional<gasp::Isometry3> T) {
      if (T) *T = *T * Q_inv;
      return T;
    };
    auto truth = [&](std::size_t i) { return turnedBack(ds.groundTruthOf(i, gt_offset)); };
    // The reference T_target_source of pair (i, j), the target's camera rolled by --roll-target.
    const gasp::Isometry3 T_rolled_target = gasp::turnRotation(roll_target);
    auto pairTruth = [&](std::size_t i, std::size_t j) -> std::optional<gasp::Isometry3> {
      if (!truth(i) || !truth(j)) return std::nullopt;
      return gasp::Isometry3(T_rolled_target * gasp::relativePose(*truth(j), *truth(i)));
    };
    auto needsColour = [](const std::string& method) {
      return method == "cshot" || method == "sift" || method == "dsift";
    };
    auto hasRgb = [&](std::size_t i) { return ds.frame(i).rgb_path.has_value(); };

    // Rolling-shutter deskew before segmentation (rolling_shutter_deskew.h): the velocity from
    // GASP's registration of frames i-1 and i+1, or (diagnostic) from the reference.
    FrameCache::DepthFilter filter;
    std::set<std::size_t> deskew_frames, deskewed;  // frames, once each (a frame may be loaded again)
    std::vector<double> deskew_ms;
    if (deskew.readout_s != 0.0 && twist_from == "truth") {
      filter = [&](std::size_t i, const cv::Mat& depth) {
        deskew_frames.insert(i);
        // The reference samples nearest to 20 ms either side, and the time between them.
        const double t = ds.frame(i).timestamp + gt_offset;
        const auto& gt = ds.groundTruth();
        const auto a = gasp::findNearest(gt, t - 0.02, 0.02), b = gasp::findNearest(gt, t + 0.02, 0.02);
        if (!a || !b || *a == *b) return depth;
        deskewed.insert(i);
        return gasp::deskewDepth(depth, ds.intrinsics(),
                                 gasp::twistBetween(gt[*a].T_world_camera, gt[*b].T_world_camera,
                                                    gt[*b].timestamp - gt[*a].timestamp),
                                 deskew.readout_s);
      };
    } else if (deskew.readout_s != 0.0) {
      filter = [&](std::size_t i, const cv::Mat& depth) {
        deskew_frames.insert(i);
        const auto t0 = Clock::now();
        auto out = gasp::deskewTumFrame(ds, i, depth, deskew, base);
        deskew_ms.push_back(msSince(t0));
        if (!out.deskewed) {
          std::fprintf(stderr, "frame %zu not deskewed: %s\n", i, out.reason.c_str());
          return depth;
        }
        deskewed.insert(i);
        return out.depth_m;
      };
    }
    FrameCache cache(ds, filter);
    // One method on one pair (i -> j): i is the source, j the target.
    auto runMethod = [&](const std::string& method, std::size_t i, std::size_t j, Picture* picture,
                         const std::optional<gasp::Isometry3>& T_gt,
                         const std::optional<gasp::Isometry3>& T_ref_icp = std::nullopt) {
      MethodRun run;
      if (isGasp(method)) {
        gasp::PairParams params = base;
        params.refine = method != "gasp-norefine";
        const auto& va = cache.gaspView(i, params.superpixels);
        const auto& vb = cache.gaspView(j, params.superpixels, roll_target);
        const auto t0 = Clock::now();
        const auto r = gasp::registerViews(va.view, vb.view, params);
        const double reg_ms = msSince(t0);
        run.estimated = r.pose.success;
        run.T_target_source = r.pose.T_target_source;
        run.reason = r.pose.reason;
        run.ms = va.ms + vb.ms + reg_ms;
        run.associations = r.association.associations.size();
        run.inliers = r.pose.num_inliers;
        run.violation_ratio = r.visibility.violation_ratio;
        run.consistent = r.visibility.consistent, run.occluded = r.visibility.occluded;
        run.violations = r.visibility.violations;
        run.occluded_ratio = r.visibility.occluded_ratio;
        run.one_way = r.used_one_way ? 1 : 0;
        run.guided_support = r.guided_support;
        run.finer_scale = r.retry_views != nullptr;
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
          const auto g = gasp::baselines::polishPose(va.view.depth_m, vb.view.depth_m, va.view.intrinsics,
                                                     r.pose.T_target_source);
          if (!g.success) {
            run.reason = "GICP: " + g.reason + "; GASP's pose kept";
          } else {
            const auto check = gasp::checkVisibility(va.view, vb.view, g.T_target_source, base.visibility);
            if (check.passed) {
              run.T_target_source = g.T_target_source;
              run.violation_ratio = check.violation_ratio;
              run.consistent = check.consistent, run.occluded = check.occluded, run.violations = check.violations;
              run.occluded_ratio = check.occluded_ratio;
            } else {
              run.reason = "GICP's pose failed the visibility check (" + check.reason + "); GASP's pose kept";
            }
          }
          gicp_ms = msSince(t1);
          run.ms += gicp_ms;
        }
#endif
        // The views r's patch indices refer to (the finer-scale retry's when it gave the estimate).
        const auto [pva, pvb] = gasp::viewsOf(r, va.view, vb.view);
        if (T_gt) {
          const auto& sa = pva->segmentation;
          const auto& sb = pvb->segmentation;
          run.free_quality = gasp::evaluateAssociations(r.association.associations, sa, sb, pvb->depth_m,
                                                        pvb->intrinsics, *T_gt);
          run.verified_quality =
              gasp::evaluateAssociations(r.verified, sa, sb, pvb->depth_m, pvb->intrinsics, *T_gt);
          if (T_ref_icp)
            run.verified_quality_polished =
                gasp::evaluateAssociations(r.verified, sa, sb, pvb->depth_m, pvb->intrinsics, *T_ref_icp);
          run.agreement_truth = gasp::depthAgreement(va.view, vb.view, *T_gt, 4);
          if (r.pose.success) {
            run.agreement_estimate = gasp::depthAgreement(va.view, vb.view, run.T_target_source, 4);
          }
          if (r.pose.success && method != "gasp-gicp") {  // the information is of GASP's pose
            try {  // a diagnostic: an information it cannot use leaves the columns empty
              run.nees = gasp::eval::neesParts(r.pose.T_target_source, *T_gt, r.edge_information);
              run.nees_refinement = gasp::eval::nees(r.pose.T_target_source, *T_gt, r.pose.information);
            } catch (const gasp::Error&) {
            }
          }
        }
        run.stage_ms = {{"segmentation", va.ms + vb.ms + r.timings.retry_segmentation_ms},
                        {"association", r.timings.association_ms},
                        {"ransac", r.timings.ransac_ms},
                        {"refinement+check", reg_ms - r.timings.retry_segmentation_ms - r.timings.association_ms -
                                                 r.timings.ransac_ms}};
        if (method == "gasp-gicp" && r.pose.success) run.stage_ms["gicp+check"] = gicp_ms;
        if (picture) {
          std::vector<unsigned char> correct;
          if (T_gt)
            for (const auto& a : r.association.associations)
              correct.push_back(gasp::isSameSurface(pva->segmentation.patches[static_cast<std::size_t>(a.a)],
                                                    pvb->segmentation.patches[static_cast<std::size_t>(a.b)], *T_gt));
          picture->image = gasp::drawAssociations(pva->depth_m, pva->segmentation, pva->intrinsics,
                                                  pvb->depth_m, pvb->segmentation, pvb->intrinsics,
                                                  r.association.associations, correct);
          picture->shown = r.association.associations.size();
          picture->correct = static_cast<std::size_t>(std::count(correct.begin(), correct.end(), 1));
        }
        return run;
      }
#ifdef GASP_HAVE_BASELINES
      if (method == "gicp") {
        // ICP without a start: GICP from the identity (icp_polish.h: voxel-sampled clouds, 5 cm
        // correspondence gate), then the visibility check every method's pose must pass. The
        // depth as the baselines get it (undistorted where the lens is; never deskewed).
        gasp::DepthView va, vb;  // the check reads only depth and intrinsics
        va.depth_m = cache.rgbd(i).depth_m, va.intrinsics = cache.rgbd(i).intrinsics;
        vb.depth_m = cache.rgbd(j).depth_m, vb.intrinsics = cache.rgbd(j).intrinsics;
        const auto t0 = Clock::now();
        const auto g = gasp::baselines::polishPose(va.depth_m, vb.depth_m, va.intrinsics, gasp::Isometry3::Identity());
        const double icp_ms = msSince(t0);
        run.T_target_source = g.T_target_source;
        if (!g.success) {
          run.reason = "GICP: " + g.reason;
        } else {
          const auto check = gasp::checkVisibility(va, vb, g.T_target_source, base.visibility);
          run.violation_ratio = check.violation_ratio;
          run.consistent = check.consistent, run.occluded = check.occluded, run.violations = check.violations;
          run.occluded_ratio = check.occluded_ratio;
          run.estimated = check.passed;
          if (!check.passed) run.reason = check.reason;
        }
        if (run.estimated && T_gt) run.agreement_estimate = gasp::depthAgreement(va, vb, run.T_target_source, 4);
        run.ms = msSince(t0);
        run.stage_ms = {{"gicp", icp_ms}, {"check", run.ms - icp_ms}};
        return run;
      }
      const auto m = gasp::baselines::parseMethod(method);
      const auto& ka = cache.described(i, m, baseline);
      const auto& kb = cache.described(j, m, baseline);
      const auto t0 = Clock::now();
      const auto r = gasp::baselines::registerDescribed(cache.rgbd(i), cache.rgbd(j), ka, kb, baseline);
      const double reg_ms = msSince(t0);
      run.estimated = r.pose.success;
      run.T_target_source = r.pose.T_target_source;
      run.reason = r.pose.reason;
      run.ms = ka.describe_ms + kb.describe_ms + reg_ms;
      run.associations = r.matches.size();
      run.inliers = r.pose.num_inliers;
      run.violation_ratio = r.visibility.violation_ratio;
      run.consistent = r.visibility.consistent, run.occluded = r.visibility.occluded;
      run.violations = r.visibility.violations;
      run.occluded_ratio = r.visibility.occluded_ratio;
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
          if (T_gt)
            correct.push_back((*T_gt * r.correspondences[k].p_source - r.correspondences[k].p_target).norm() <= 0.05);
        }
        auto image = [&](std::size_t f) {
          const auto& v = cache.rgbd(f);
          if (!v.bgr.empty()) return v.bgr;
          cv::Mat grey;  // no colour: the depth, scaled to 0..5 m
          v.depth_m.convertTo(grey, CV_8U, 255.0 / 5.0);
          return grey;
        };
        picture->image = gasp::baselines::drawKeypointMatches(image(i), image(j), r.source.pixels, r.target.pixels, ma,
                                                              mb, correct);
        picture->shown = r.matches.size();
        picture->correct = static_cast<std::size_t>(std::count(correct.begin(), correct.end(), 1));
      }
#endif
      return run;
    };

    // Pictures of one pair first (not scored).
    if (!picture_pair.empty()) {
      const std::size_t i = picture_pair[0], j = picture_pair[1];
      if (i >= ds.size() || j >= ds.size()) throw gasp::Error("--picture: frame index beyond the folder's frames");
      const std::optional<gasp::Isometry3> T_gt = pairTruth(i, j);
      for (const auto& method : methods) {
        if (needsColour(method) && (!hasRgb(i) || !hasRgb(j))) {
          std::printf("picture %s: n/a (no rgb)\n", method.c_str());
          continue;
        }
        if (method == "gicp") {  // no associations to draw
          std::printf("picture %s: n/a (GICP has no associations)\n", method.c_str());
          continue;
        }
        Picture pic;
        const MethodRun run = runMethod(method, i, j, &pic, T_gt);
        const std::string path = picture_prefix + method + "." + picture_format;
        gasp::writeImage(path, pic.image, "picture");
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
    std::vector<std::pair<std::size_t, std::size_t>> all;  // (from, skip)
    std::map<std::size_t, std::size_t> pairs_per_skip;
    for (const std::size_t skip : skips) {
      auto pairs = gasp::eval::makePairs(ds.size(), skip, starts_every);
      // Only pairs where both frames have ground truth can be scored.
      pairs.erase(std::remove_if(pairs.begin(), pairs.end(), [&](const auto& p) {
                    return !truth(p.first) || !truth(p.second);
                  }), pairs.end());
      if (max_pairs > 0 && pairs.size() > max_pairs) pairs.resize(max_pairs);
      pairs_per_skip[skip] = pairs.size();
      for (const auto& p : pairs) all.emplace_back(p.first, skip);
    }
    std::stable_sort(all.begin(), all.end(), [](const auto& a, const auto& b) { return a.first < b.first; });

    std::map<std::string, std::vector<gasp::eval::PairOutcome>> by_method;
    std::map<std::string, std::map<std::string, std::vector<double>>> stage_ms;  // method -> stage -> ms
    std::map<std::pair<std::size_t, std::string>, std::size_t> no_rgb;  // (skip, method) -> pairs left out
    std::ofstream pairs_csv;
    if (!pairs_csv_path.empty()) {
      pairs_csv.open(pairs_csv_path);
      if (!pairs_csv) throw gasp::Error("cannot write " + pairs_csv_path);
      pairs_csv << "skip,method,from,to,estimated,t_err_m,r_err_deg,ms,associations,inliers,violation_ratio,occluded_ratio,consistent,occluded,violations,one_way,guided_support,finer_scale,slide_moved,dense_terms,dense_rounds,dense_last_step_m,dense_shortened,dense_stopped,"
                    "precision,verified,verified_precision,verified_density,agreement,agreement_truth,tx,ty,tz,qx,qy,qz,qw,"
                    "motion_t_m,motion_r_deg,ref_icp_t_m,ref_icp_r_deg,est_vs_ref_icp_t_m,est_vs_ref_icp_r_deg,"
                    "est_icp_t_m,est_icp_r_deg,icp_est_vs_ref_icp_t_m,icp_est_vs_ref_icp_r_deg,verified_precision_ref_icp,"
                    "rgb_inliers,rgb_parallax_px,rgb_r_vs_ref_deg,rgb_r_vs_est_deg,rgb_r_vs_ref_icp_deg,nees,nees_t,nees_r,nees_refinement,reason\n";
    }
    // GICP from T_init between the views GASP registers (undistorted where the intrinsics have
    // distortion; the depth is the cached one); none without the baselines or when it fails.
    auto polish = [&]([[maybe_unused]] std::size_t i, [[maybe_unused]] std::size_t j,
                      [[maybe_unused]] const gasp::Isometry3& T_init) -> std::optional<gasp::Isometry3> {
#ifdef GASP_HAVE_BASELINES
      const auto& va = cache.gaspView(i, base.superpixels).view;
      const auto& vb = cache.gaspView(j, base.superpixels).view;
      const auto r = gasp::baselines::polishPose(va.depth_m, vb.depth_m, va.intrinsics, T_init);
      if (r.success) return r.T_target_source;
#endif
      return std::nullopt;
    };
    // Translation [m] and rotation [deg] of A^-1 B, or two empty CSV fields.
    auto difference = [](const std::optional<gasp::Isometry3>& A, const std::optional<gasp::Isometry3>& B) {
      if (!A || !B) return std::string(",");
      const gasp::Isometry3 E = A->inverse() * *B;
      return std::to_string(gasp::translationNorm(E)) + ',' + std::to_string(gasp::rotationAngle(E) * 180.0 / M_PI);
    };
    // The depth-free check (--rgb-rotation-check): the rotation between the two colour images from
    // their pixels alone, and the reference's short motions between each frame's depth and rgb
    // stamps, so that poses between the depth frames can be compared with it.
    struct RgbCheck {
      bool ran = false;                                   // both frames have rgb
      std::size_t inliers = 0;
      double parallax_px = 0.0;
      std::optional<Eigen::Matrix3d> R_rgb;               // R_target_source from the images
      std::optional<gasp::Isometry3> T_ref;               // the reference between the rgb stamps
      std::optional<gasp::Isometry3> T_di_ri, T_rj_dj;    // rgb i -> depth i, depth j -> rgb j
    };
    auto poseAt = [&](double t) { return turnedBack(ds.groundTruthAt(t + gt_offset)); };
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
    auto rgbCheck = [&]([[maybe_unused]] std::size_t i, [[maybe_unused]] std::size_t j) {
      RgbCheck c;
#ifdef GASP_HAVE_BASELINES
      if (!hasRgb(i) || !hasRgb(j)) return c;
      const auto& fi = ds.frame(i);
      const auto& fj = ds.frame(j);
      c.ran = true;
      const auto e = gasp::baselines::estimateEpipolarRotation(cache.rgbd(i).bgr, cache.rgbd(j).bgr, rgb_camera, epipolar);
      c.inliers = e.inliers;
      c.parallax_px = e.median_parallax_px;
      if (e.success) c.R_rgb = e.R_target_source;
      const auto ri = poseAt(*fi.rgb_timestamp), rj = poseAt(*fj.rgb_timestamp);
      const auto di = poseAt(fi.timestamp), dj = poseAt(fj.timestamp);
      if (ri && rj) c.T_ref = gasp::relativePose(*rj, *ri);
      if (ri && di) c.T_di_ri = gasp::relativePose(*di, *ri);
      if (rj && dj) c.T_rj_dj = gasp::relativePose(*rj, *dj);
#endif
      return c;
    };
    // The rotation [deg] between the images' rotation and a pose between the rgb stamps, or "".
    auto rgbAngle = [](const RgbCheck& c, const std::optional<gasp::Isometry3>& T_rgb) {
      if (!c.R_rgb || !T_rgb) return std::string();
      const Eigen::AngleAxisd d(c.R_rgb->transpose() * T_rgb->linear());
      return std::to_string(std::abs(d.angle()) * 180.0 / M_PI);
    };
    // A pose between the depth stamps, carried to the rgb stamps by the reference's short motions.
    auto toRgbStamps = [](const RgbCheck& c, const std::optional<gasp::Isometry3>& T_dj_di) -> std::optional<gasp::Isometry3> {
      if (!T_dj_di || !c.T_di_ri || !c.T_rj_dj) return std::nullopt;
      return gasp::Isometry3(*c.T_rj_dj * *T_dj_di * *c.T_di_ri);
    };
    const auto bench_t0 = Clock::now();
    std::size_t done = 0;
    for (const auto& [i, skip] : all) {
      cache.dropBefore(i);
      const std::size_t j = i + skip;
      const gasp::Isometry3 T_gt = *pairTruth(i, j);
      // The reference polished by GICP (once per pair): how far the depth pulls it, and where to.
      const std::optional<gasp::Isometry3> T_ref_icp =
          polish_reference ? polish(i, j, T_gt) : std::nullopt;
      const RgbCheck rgb = rgb_rotation_check ? rgbCheck(i, j) : RgbCheck{};
      for (const auto& method : methods) {
        if (needsColour(method) && (!hasRgb(i) || !hasRgb(j))) {
          ++no_rgb[{skip, method}];
          continue;
        }
        const MethodRun run = runMethod(method, i, j, nullptr, T_gt, T_ref_icp);
        gasp::eval::PairOutcome o;
        o.skip = skip;
        o.from = i;
        o.to = j;
        o.ms = run.ms;
        o.estimated = run.estimated;
        o.reason = run.reason;
        if (run.estimated) gasp::eval::scorePose(run.T_target_source, T_gt, o);
        for (const auto& [stage, ms] : run.stage_ms) stage_ms[method][stage].push_back(ms);
        by_method[method].push_back(o);
        if (pairs_csv) {
          pairs_csv << skip << ',' << method << ',' << i << ',' << j << ',' << (o.estimated ? 1 : 0) << ',';
          if (o.estimated) pairs_csv << o.t_err_m << ',' << o.r_err_deg;  // no error without an estimate
          else pairs_csv << ',';
          pairs_csv << ',' << o.ms << ',' << run.associations << ',' << run.inliers
                    << ',' << run.violation_ratio << ',' << run.occluded_ratio << ',' << run.consistent << ',' << run.occluded << ','
                    << run.violations << ',' << run.one_way << ',' << run.guided_support << ',' << (run.finer_scale ? 1 : 0)
                    << ',' << (run.slide_moved ? 1 : 0) << ',' << run.dense_terms << ',' << run.dense_rounds << ',' << run.dense_last_step_m << ','
                    << run.dense_shortened << ',' << (run.dense_stopped ? 1 : 0) << ',';
          const auto& fq = run.free_quality;
          const auto& vq = run.verified_quality;
          if (fq) pairs_csv << fq->precision();
          pairs_csv << ',';
          if (vq) pairs_csv << vq->associations << ',' << vq->precision() << ',' << vq->density();
          else pairs_csv << ",,";
          pairs_csv << ',';
          if (run.agreement_estimate) pairs_csv << *run.agreement_estimate;
          pairs_csv << ',';
          if (run.agreement_truth) pairs_csv << *run.agreement_truth;
          if (run.estimated) {
            const Eigen::Quaterniond q(run.T_target_source.linear());
            const auto& t = run.T_target_source.translation();
            pairs_csv << ',' << t.x() << ',' << t.y() << ',' << t.z() << ',' << q.x() << ',' << q.y() << ',' << q.z()
                      << ',' << q.w();
          } else {
            pairs_csv << ",,,,,,,";
          }
          // The true motion of the pair (how far apart the views are).
          pairs_csv << ',' << gasp::translationNorm(T_gt) << ',' << gasp::rotationAngle(T_gt) * 180.0 / M_PI;
          std::optional<gasp::Isometry3> T_est;
          if (run.estimated) T_est = run.T_target_source;
          const auto T_est_icp = T_est && polish_reference ? polish(i, j, *T_est) : std::nullopt;
          pairs_csv << ',' << difference(T_gt, T_ref_icp) << ',' << difference(T_est, T_ref_icp) << ','
                    << difference(T_est, T_est_icp) << ',' << difference(T_est_icp, T_ref_icp) << ',';
          if (run.verified_quality_polished) pairs_csv << run.verified_quality_polished->precision();
          pairs_csv << ',';
          if (rgb.ran) pairs_csv << rgb.inliers << ',' << rgb.parallax_px;
          else pairs_csv << ',';
          pairs_csv << ',' << rgbAngle(rgb, rgb.T_ref) << ',' << rgbAngle(rgb, toRgbStamps(rgb, T_est)) << ','
                    << rgbAngle(rgb, toRgbStamps(rgb, T_ref_icp)) << ',';
          if (run.nees) pairs_csv << run.nees->all << ',' << run.nees->translation << ',' << run.nees->rotation;
          else pairs_csv << ",,";
          pairs_csv << ',';
          if (run.nees_refinement) pairs_csv << *run.nees_refinement;
          pairs_csv << ",\"" << o.reason << "\"\n";
        }
      }
      ++done;
      std::fprintf(stderr, "\rpair %zu/%zu (%.0f s)", done, all.size(), msSince(bench_t0) / 1000.0);
      std::fflush(stderr);
    }
    if (!all.empty()) std::fprintf(stderr, "\n");

    std::vector<gasp::eval::SkipSummary> rows;
    std::size_t total_pairs = 0;
    std::printf("%-6s %-14s %6s %6s %10s %11s %8s %13s %10s\n", "skip", "method", "pairs", "failed", "rmse_t_m",
                "rmse_r_deg", "fail_%", "within5cm2deg%", "median_ms");
    for (const std::size_t skip : skips)
      for (const auto& method : methods) {
        const auto s = gasp::eval::summarise(by_method[method], skip, method);
        total_pairs += s.pairs;
        const auto na = no_rgb.find({skip, method});
        if (s.pairs == 0 && na != no_rgb.end()) {
          std::printf("%-6zu %-14s n/a (no rgb: %zu pairs left out)\n", skip, method.c_str(), na->second);
          continue;
        }
        if (s.pairs == 0) {  // no start frame with ground truth for this skip: nothing scored
          std::printf("%-6zu %-14s %6zu  no pair with ground truth for both frames\n", skip, method.c_str(), s.pairs);
          continue;
        }
        rows.push_back(s);
        if (std::isfinite(s.rmse_t_m))
          std::printf("%-6zu %-14s %6zu %6zu %10.4f %11.3f %8.1f %13.1f %10.1f", s.skip, s.method.c_str(), s.pairs,
                      s.failed, s.rmse_t_m, s.rmse_r_deg, s.fail_pct, s.within_pct, s.median_ms);
        else  // every pair failed: there is no error to average
          std::printf("%-6zu %-14s %6zu %6zu %10s %11s %8.1f %13.1f %10.1f", s.skip, s.method.c_str(), s.pairs, s.failed,
                      "n/a", "n/a", s.fail_pct, s.within_pct, s.median_ms);
        if (na != no_rgb.end()) std::printf("  (%zu of %zu pairs without rgb left out)", na->second, pairs_per_skip[skip]);
        std::printf("\n");
      }
    for (const auto& method : methods) {
      const auto st = stage_ms.find(method);
      if (st == stage_ms.end()) continue;
      std::printf("median_ms_per_stage %s:", method.c_str());
      for (const auto& [stage, v] : st->second) std::printf(" %s %.1f", stage.c_str(), median(v));
      std::printf("\n");
    }
    if (roll_target != 0)
      std::printf("roll_target: %d deg clockwise (each pair's target view turned; scored against the rolled reference)\n",
                  roll_target);
    if (deskew.readout_s != 0.0) {
      std::printf("rolling_shutter: readout %.4f s, velocity from %s, %zu of %zu frames deskewed", deskew.readout_s,
                  twist_from.c_str(), deskewed.size(), deskew_frames.size());
      if (!deskew_ms.empty())
        std::printf(", median %.1f ms per frame for the neighbours and the deskew (not in the pair times)",
                    median(deskew_ms));
      std::printf("\n");
    }
    std::printf("wall_time_s: %.1f\n", msSince(bench_t0) / 1000.0);
    if (!csv_path.empty()) {
      std::ofstream csv(csv_path);
      if (!csv) throw gasp::Error("cannot write " + csv_path);
      csv << gasp::eval::csvHeader() << '\n';
      for (const auto& s : rows) csv << gasp::eval::csvRow(s) << '\n';
    }
    if (total_pairs == 0 && picture_pair.empty()) {
      std::fprintf(stderr, "no pair with ground truth for both frames\n");
      return 4;
    }
  } catch (const gasp::Error& e) {
    std::cerr << "error: " << e.what() << '\n';
    return 1;
  } catch (const std::exception& e) {  // e.g. a cv::Exception from a library
    std::cerr << "error: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
