// gasp-pairs: the paper's pair benchmark on a TUM folder.
//   gasp-pairs --tum DIR [--skips 10,20,30,40] [--starts-every N] [--method gasp,gasp-norefine]
//              [--csv OUT.csv] [--pairs-csv OUT_pairs.csv] [--max-pairs N]
// Pairs (i, i + skip) from start frames 0, N, 2N, ... (indices in depth.txt order); for each pair
// both views are segmented, associated and registered; the relative pose is compared with ground
// truth. Prints one table row per skip and method (definitions in gasp/eval/pair_protocol.h and
// docs/evaluation.md); progress goes to stderr. Exit codes: 0 done, 1 bad input, 2 usage error,
// 4 no pair with ground truth.
#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>

#include "gasp/core/error.h"
#include "gasp/core/tum_dataset.h"
#include "gasp/core/tum_trajectory.h"
#include "gasp/eval/pair_protocol.h"
#include "gasp/pipeline/pair_registration.h"

namespace {

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"gasp-pairs: relative-pose benchmark over frame pairs of a TUM RGB-D folder (the GASP paper's protocol)"};
  std::string tum_dir, intrinsics_arg, csv_path, pairs_csv_path;
  std::vector<std::size_t> skips{10, 20, 30, 40};
  std::vector<std::string> methods{"gasp"};
  std::size_t starts_every = 10, max_pairs = 0;
  app.add_option("--tum", tum_dir, "TUM RGB-D folder")->required();
  app.add_option("--skips", skips, "frame skips (in depth.txt order)")->delimiter(',')->capture_default_str();
  app.add_option("--starts-every", starts_every, "start frames 0, N, 2N, ...")->capture_default_str()->check(CLI::PositiveNumber);
  app.add_option("--method", methods, "gasp (full pipeline) and/or gasp-norefine (RANSAC only)")
      ->delimiter(',')->check(CLI::IsMember({"gasp", "gasp-norefine"}))->capture_default_str();
  app.add_option("--intrinsics", intrinsics_arg, "fr1|fr2|fr3|ros or an intrinsics file (default: the folder's)");
  app.add_option("--csv", csv_path, "write the table as CSV");
  app.add_option("--pairs-csv", pairs_csv_path, "write one line per pair and method");
  app.add_option("--max-pairs", max_pairs, "at most this many pairs per skip (0 = all)");
  gasp::PairParams base;
  app.add_option("--k", base.association.feature_sets.neighbourhood.k, "association neighbourhood size (0 = full view)")->capture_default_str();
  app.add_option("--candidates", base.association.candidates, "KD-tree candidates per patch (C)")->capture_default_str();
  app.add_option("--lambda", base.association.lambda, "gating on the normalised edit distance")->capture_default_str();
  app.add_flag("!--no-mutual", base.association.mutual_check, "keep one-way best partners too (no mutual check)");
  app.add_option("--min-inliers", base.pose.ransac.min_inliers, "RANSAC: fewer inliers give no estimate")->capture_default_str();
  app.add_option("--dense-rounds", base.dense_rounds, "dense projective refinement rounds (0 = none)")->capture_default_str();
  app.add_option("--pixel-step", base.projective.pixel_step, "dense terms: every N-th pixel")->capture_default_str();
  double gt_offset = 0.0;
  app.add_option("--gt-offset", gt_offset,
                 "look ground truth up at depth timestamp + OFFSET [s] (nearest within 0.02 s; TUM fr1 depth lags "
                 "the motion capture, -0.02 fits better)")->capture_default_str();
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;  // --help: 0; any usage error: 2
  }
  try {
    gasp::TumDataset::Options opt;
    if (!intrinsics_arg.empty()) opt.intrinsics = gasp::CameraIntrinsics::fromPresetOrFile(intrinsics_arg);
    const auto ds = gasp::TumDataset::open(tum_dir, opt);
    // Ground truth of frame i: the frame's own association (offset 0) or a look-up at t + offset.
    auto truth = [&](std::size_t i) -> std::optional<gasp::Isometry3> {
      if (gt_offset == 0.0) return ds.frame(i).T_world_camera;
      const auto k = gasp::findNearest(ds.groundTruth(), ds.frame(i).timestamp + gt_offset, 0.02);
      if (!k) return std::nullopt;
      return ds.groundTruth()[*k].T_world_camera;
    };
    std::vector<gasp::eval::PairOutcome> outcomes;
    std::map<std::string, std::vector<gasp::eval::PairOutcome>> by_method;
    std::map<std::string, std::map<std::string, std::vector<double>>> stage_ms;  // method -> stage -> ms
    std::ofstream pairs_csv;
    if (!pairs_csv_path.empty()) {
      pairs_csv.open(pairs_csv_path);
      if (!pairs_csv) throw gasp::Error("cannot write " + pairs_csv_path);
      pairs_csv << "skip,method,from,to,estimated,t_err_m,r_err_deg,ms,associations,inliers,violation_ratio,reason\n";
    }
    for (const std::size_t skip : skips) {
      auto pairs = gasp::eval::makePairs(ds.size(), skip, starts_every);
      // Only pairs where both frames have ground truth can be scored.
      pairs.erase(std::remove_if(pairs.begin(), pairs.end(), [&](const auto& p) {
                    return !truth(p.first) || !truth(p.second);
                  }), pairs.end());
      if (max_pairs > 0 && pairs.size() > max_pairs) pairs.resize(max_pairs);
      std::size_t done = 0;
      for (const auto& [i, j] : pairs) {
        for (const auto& method : methods) {
          const auto t0 = std::chrono::steady_clock::now();
          gasp::PairParams params = base;
          params.refine = method == "gasp";
          const auto va = gasp::makeDepthView(ds.loadDepth(i), ds.intrinsics(), params.superpixels);
          const auto vb = gasp::makeDepthView(ds.loadDepth(j), ds.intrinsics(), params.superpixels);
          const double seg_ms = va.segmentation.timings.total() + vb.segmentation.timings.total();
          const auto r = gasp::registerViews(va, vb, params);
          gasp::eval::PairOutcome o;
          o.skip = skip;
          o.from = i;
          o.to = j;
          o.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
          o.estimated = r.pose.success;
          o.reason = r.pose.reason;
          if (r.pose.success) {
            const gasp::Isometry3 T_gt = gasp::relativePose(*truth(j), *truth(i));
            gasp::eval::scorePose(r.pose.T_target_source, T_gt, o);
          }
          auto& st = stage_ms[method];
          st["segmentation"].push_back(seg_ms);
          st["association"].push_back(r.timings.association_ms);
          st["ransac"].push_back(r.timings.ransac_ms);
          st["refinement"].push_back(r.timings.refine_ms + r.timings.dense_ms);
          by_method[method].push_back(o);
          if (pairs_csv) {
            pairs_csv << skip << ',' << method << ',' << i << ',' << j << ',' << (o.estimated ? 1 : 0) << ','
                      << o.t_err_m << ',' << o.r_err_deg << ',' << o.ms << ',' << r.association.associations.size() << ','
                      << r.pose.num_inliers << ',' << r.visibility.violation_ratio << ",\"" << o.reason << "\"\n";
          }
        }
        ++done;
        std::fprintf(stderr, "\rskip %zu: pair %zu/%zu", skip, done, pairs.size());
        std::fflush(stderr);
      }
      if (!pairs.empty()) std::fprintf(stderr, "\n");
    }
    std::vector<gasp::eval::SkipSummary> rows;
    for (const std::size_t skip : skips)
      for (const auto& method : methods) rows.push_back(gasp::eval::summarise(by_method[method], skip, method));
    std::size_t total_pairs = 0;
    for (const auto& s : rows) total_pairs += s.pairs;
    std::printf("%-6s %-14s %6s %6s %10s %11s %8s %13s %10s\n", "skip", "method", "pairs", "failed", "rmse_t_m",
                "rmse_r_deg", "fail_%", "within5cm2deg%", "median_ms");
    for (const auto& s : rows)
      std::printf("%-6zu %-14s %6zu %6zu %10.4f %11.3f %8.1f %13.1f %10.1f\n", s.skip, s.method.c_str(), s.pairs,
                  s.failed, s.rmse_t_m, s.rmse_r_deg, s.fail_pct, s.within_pct, s.median_ms);
    for (const auto& [method, st] : stage_ms) {
      std::printf("median_ms_per_stage %s:", method.c_str());
      for (const auto& [stage, v] : st) std::printf(" %s %.1f", stage.c_str(), median(v));
      std::printf("\n");
    }
    if (!csv_path.empty()) {
      std::ofstream csv(csv_path);
      if (!csv) throw gasp::Error("cannot write " + csv_path);
      csv << gasp::eval::csvHeader() << '\n';
      for (const auto& s : rows) csv << gasp::eval::csvRow(s) << '\n';
    }
    if (total_pairs == 0) {
      std::fprintf(stderr, "no pair with ground truth for both frames\n");
      return 4;
    }
  } catch (const gasp::Error& e) {
    std::cerr << "error: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
