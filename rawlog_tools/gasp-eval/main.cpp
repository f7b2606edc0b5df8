// gasp-eval: trajectory accuracy with the TUM RGB-D benchmark's definitions.
//   gasp-eval ate --gt GT.txt --est EST.txt [--max-dt 0.02] [--offset 0] [--scale 1] [--aligned OUT.txt]
//   gasp-eval rpe --gt GT.txt --est EST.txt [--delta 1 --delta-unit frames|s] [--max-dt 0.02]
// Exit codes: 0 success, 1 bad input (message on stderr), 2 usage error.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <iostream>
#include <map>

#include "gasp/core/error.h"
#include "gasp/eval/ate.h"
#include "gasp/eval/rpe.h"
#include "cli.h"
#include "params_options.h"

namespace {

void printStats(const std::string& name, const gasp::eval::ErrorStatistics& s, const char* unit) {
  for (const auto& [key, value] : std::initializer_list<std::pair<const char*, double>>{
           {"rmse", s.rmse}, {"mean", s.mean}, {"median", s.median}, {"std", s.std},
           {"min", s.min}, {"max", s.max}})
    std::printf("%s.%s: %.6f %s\n", name.c_str(), key, value, unit);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"gasp-eval: absolute trajectory error (ATE) and relative pose error (RPE) of an "
               "estimated TUM trajectory against ground truth, as TUM's evaluate_ate.py and "
               "evaluate_rpe.py define them"};
  // The params file is not used here; it is checked, and --print-params prints it, as in every program.
  gasp::tools::ParamsOptions params_options;
  gasp::SlamParams params;
  if (!params_options.preload(argc, argv, params)) return 1;
  if (const int code = params_options.printBeforeParse(params); code >= 0) return code;
  params_options.add(app);
  app.require_subcommand(1);
  std::string gt_path, est_path, aligned_path;
  double max_dt = 0.02, offset = 0.0, scale = 1.0, delta = 1.0;
  std::string delta_unit = "s";

  auto* ate = app.add_subcommand("ate", "absolute trajectory error after rigid alignment (no scale)");
  auto* rpe = app.add_subcommand("rpe", "relative pose error over a fixed delta");
  for (auto* sub : {ate, rpe}) {
    sub->fallthrough();  // --params after the subcommand too
    sub->add_option("--gt", gt_path, "ground-truth trajectory (TUM format)")->required();
    sub->add_option("--est", est_path, "estimated trajectory (TUM format)")->required();
    sub->add_option("--max-dt", max_dt, "timestamp association window [s]")->capture_default_str()->check(gasp::tools::above(0));
    sub->add_option("--offset", offset, "time offset added to the estimate [s]")->capture_default_str()->check(gasp::tools::finite());
    sub->add_option("--scale", scale, "scale applied to the estimate's translations")->capture_default_str()->check(gasp::tools::above(0));
  }
  ate->add_option("--aligned", aligned_path, "write the estimate, aligned to the ground truth, as a TUM file");
  rpe->add_option("--delta", delta, "step between the poses of a pair")->capture_default_str()->check(gasp::tools::above(0));
  rpe->add_option("--delta-unit", delta_unit, "unit of --delta: frames (f) or seconds (s)")
      ->check(CLI::IsMember({"frames", "f", "s"}))
      ->capture_default_str();
  if (const int code = gasp::tools::parseCommandLine(app, argc, argv); code >= 0) return code;

  try {
    gasp::tools::RunOutputs outputs({{"--aligned", aligned_path}}, {gt_path, est_path});  // before the work
    const auto gt = gasp::readTumTrajectory(gt_path);
    const auto est = gasp::readTumTrajectory(est_path);
    if (ate->parsed()) {
      gasp::eval::AteOptions opt{max_dt, offset, scale};
      const auto r = gasp::eval::computeAte(gt, est, opt);
      std::printf("compared_pose_pairs: %zu\n", r.translation.count);
      printStats("absolute_translational_error", r.translation, "m");
      if (!aligned_path.empty()) {
        gasp::Trajectory aligned = est;
        for (auto& p : aligned) {
          p.T_world_camera.translation() *= scale;
          p.T_world_camera = r.T_gt_est * p.T_world_camera;
        }
        gasp::OutputFile& out = outputs.at("--aligned");
        gasp::writeTumTrajectory(out.stream(), aligned, "estimate aligned to " + gt_path + " by gasp-eval ate");
        out.commit();
        std::printf("aligned_estimate: %s\n", aligned_path.c_str());
      }
    } else {
      gasp::eval::RpeOptions opt;
      opt.delta = delta;
      opt.unit = delta_unit == "s" ? gasp::eval::DeltaUnit::Seconds : gasp::eval::DeltaUnit::Frames;
      opt.max_dt = max_dt;
      opt.offset = offset;
      opt.scale = scale;
      const auto r = gasp::eval::computeRpe(gt, est, opt);
      std::printf("compared_pose_pairs: %zu\n", r.pairs.size());
      std::printf("delta: %g %s\n", delta, delta_unit == "s" ? "s" : "frames");
      printStats("translational_error", r.translation, "m");
      printStats("rotational_error", r.rotation_deg, "deg");
    }
  } catch (const std::exception& e) {  // gasp::Error, and anything a library throws
    std::cerr << "error: " << gasp::exceptionMessage(e) << '\n';
    return 1;
  }
  return 0;
}
