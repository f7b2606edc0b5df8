// gasp-associate: dense patch associations between two depth frames of a TUM folder.
//   gasp-associate --tum DIR --from I --to J [--intrinsics P] [--k 30] [--candidates 75] [--lambda 0.5]
//                  [--r-dev 0.04] [--theta-dev 10] [--no-mutual]
// I and J are frame indices in depth.txt order. Prints the patch count of each view, the number of
// associations and, where both frames have ground truth, `precision:` and `density:` lines
// (definitions in gasp/association/association_quality.h). Exit codes: 0 associations found,
// 1 bad input, 2 usage error, 3 no association (the reason is printed).
#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <iostream>

#include "gasp/association/association_quality.h"
#include "gasp/association/view_association.h"
#include "gasp/core/error.h"
#include "gasp/core/tum_dataset.h"
#include "gasp/superpixels/depth_superpixels.h"

int main(int argc, char** argv) {
  CLI::App app{"gasp-associate: patch-to-patch associations between two depth views, from geometry alone"};
  std::string tum_dir, intrinsics_arg;
  std::size_t from = 0, to = 0;
  gasp::AssociationParams params;
  app.add_option("--tum", tum_dir, "TUM RGB-D folder")->required();
  app.add_option("--from", from, "index of view A in depth.txt order")->required();
  app.add_option("--to", to, "index of view B in depth.txt order")->required();
  app.add_option("--intrinsics", intrinsics_arg, "fr1|fr2|fr3|ros or an intrinsics file (default: the folder's)");
  app.add_option("--k", params.feature_sets.neighbourhood.k, "neighbourhood size (0 = full view)")->capture_default_str();
  app.add_option("--candidates", params.candidates, "KD-tree candidates per patch (C)")->capture_default_str();
  app.add_option("--lambda", params.lambda, "gating on the normalised edit distance")->capture_default_str();
  double theta_dev_deg = params.match.theta_dev_rad * 180.0 / M_PI;
  app.add_option("--r-dev", params.match.r_dev_m, "match tolerance of the distance components [m]")->capture_default_str();
  app.add_option("--theta-dev", theta_dev_deg, "match tolerance of the angle components [deg]")->capture_default_str();
  app.add_flag("!--no-mutual", params.mutual_check, "keep one-way best partners too (no mutual check)");
  CLI11_PARSE(app, argc, argv);
  params.match.theta_dev_rad = theta_dev_deg * M_PI / 180.0;
  try {
    gasp::TumDataset::Options opt;
    if (!intrinsics_arg.empty()) opt.intrinsics = gasp::CameraIntrinsics::fromPresetOrFile(intrinsics_arg);
    const auto ds = gasp::TumDataset::open(tum_dir, opt);
    const cv::Mat depth_a = ds.loadDepth(from), depth_b = ds.loadDepth(to);
    const auto seg_a = gasp::segmentDepthSuperpixels(depth_a, ds.intrinsics());
    const auto seg_b = gasp::segmentDepthSuperpixels(depth_b, ds.intrinsics());
    const auto result = gasp::associateViews(gasp::toPatchGeometry(seg_a.patches), gasp::toPatchGeometry(seg_b.patches), params);
    const auto& s = result.stats;
    std::printf("patches_a: %zu\npatches_b: %zu\nassociations: %zu\n", seg_a.patches.size(), seg_b.patches.size(),
                result.associations.size());
    std::printf("time_ms: segmentation %.1f + %.1f, features %.1f, kd-tree %.1f, matching %.1f\n",
                seg_a.timings.total(), seg_b.timings.total(), s.features_ms, s.tree_ms, s.matching_ms);
    std::printf("comparisons: %zu of %zu without KD-tree, %zu cut early, %zu gated out, %zu not mutual\n",
                s.comparisons, s.comparisons_full, s.cut_early, s.gated_out, s.not_mutual);
    const auto& fa = ds.frame(from);
    const auto& fb = ds.frame(to);
    if (fa.T_world_camera && fb.T_world_camera) {
      const auto q = gasp::evaluateAssociations(result.associations, seg_a, seg_b, depth_b, ds.intrinsics(),
                                                gasp::relativePose(*fb.T_world_camera, *fa.T_world_camera));
      std::printf("correct: %d\nwith_true_partner: %d\nprecision: %.3f\ndensity: %.3f\n", q.correct,
                  q.with_true_partner, q.precision(), q.density());
    } else {
      std::printf("ground truth: not available for both frames\n");
    }
    if (result.associations.empty()) {
      std::printf("no associations: %s\n", result.reason.c_str());
      return 3;
    }
  } catch (const gasp::Error& e) {
    std::cerr << "error: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
