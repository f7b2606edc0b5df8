// gasp-segment: depth superpixels of one depth image or of every frame of a TUM folder.
//   gasp-segment --depth FILE.png [--intrinsics fr1|fr2|fr3|ros|FILE] [--depth-scale 5000] --out labels.png
//   gasp-segment --tum DIR [--intrinsics ...] --out OUT_DIR [--every N]
// Prints `patches: N`, `coverage: C`, dropped pixels, patch-area statistics and time per stage.
// Exit codes: 0 success, 1 bad input (message on stderr), 2 usage error.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <numeric>

#include "gasp/core/error.h"
#include "gasp/core/image_file.h"
#include "gasp/core/tum_dataset.h"
#include "gasp/superpixels/depth_superpixels.h"
#include "gasp/superpixels/patch_repeatability.h"
#include "gasp/superpixels/segmentation_picture.h"
#include "cli.h"
#include "params_options.h"

namespace {

void report(const gasp::SuperpixelSegmentation& seg) {
  std::vector<double> areas;
  for (const auto& p : seg.patches) areas.push_back(p.area_m2 * 1e4);  // cm^2
  std::sort(areas.begin(), areas.end());
  const double n = static_cast<double>(areas.size());
  const double mean = areas.empty() ? 0.0 : std::accumulate(areas.begin(), areas.end(), 0.0) / n;
  double var = 0;
  for (double a : areas) var += (a - mean) * (a - mean);
  std::printf("patches: %zu\n", seg.patches.size());
  std::printf("coverage: %.4f\n", seg.stats.coverage());
  std::printf("valid_pixels: %zu\ndropped_pixels: %zu\n", seg.stats.valid_pixels, seg.stats.dropped_pixels);
  if (!areas.empty())
    std::printf("area_cm2: mean %.1f median %.1f min %.1f max %.1f cv %.2f\n", mean, areas[areas.size() / 2],
                areas.front(), areas.back(), mean > 0 ? std::sqrt(var / n) / mean : 0.0);
  const auto& t = seg.timings;
  std::printf("time_ms: total %.1f (cloud %.1f, normals %.1f, components %.1f, kmeans %.1f, cleanup %.1f, patches %.1f)\n",
              t.total(), t.cloud_ms, t.normals_ms, t.components_ms, t.kmeans_ms, t.cleanup_ms, t.patches_ms);
}

void writePicture(gasp::OutputFile& out, const cv::Mat& depth, const gasp::SuperpixelSegmentation& seg) {
  gasp::writeImage(out, gasp::drawSegmentation(depth, seg), "picture");
}

/// Repeatability of patches over pairs (i, i + skip); prints one line per pair and the mean.
int measurePairs(const gasp::TumDataset& ds, const gasp::SuperpixelParams& params, std::size_t skip,
                 std::size_t every) {
  double sum = 0.0;
  int pairs = 0;
  for (std::size_t i = 0; i + skip < ds.size(); i += every) {
    const auto& fa = ds.frame(i);
    const auto& fb = ds.frame(i + skip);
    if (!fa.T_world_camera || !fb.T_world_camera) continue;
    const cv::Mat depth_a = ds.loadDepth(i), depth_b = ds.loadDepth(i + skip);
    const auto sa = gasp::segmentDepthSuperpixels(depth_a, ds.intrinsics(), params);
    const auto sb = gasp::segmentDepthSuperpixels(depth_b, ds.intrinsics(), params);
    const auto r = gasp::measureRepeatability(sa, sb, depth_b, ds.intrinsics(),
                                              gasp::relativePose(*fb.T_world_camera, *fa.T_world_camera));
    if (r.in_overlap == 0) {  // nothing to repeat: not a score of 0
      std::printf("pair: %zu %zu patches %zu %zu in_overlap 0 repeatability n/a\n", i, i + skip, sa.patches.size(),
                  sb.patches.size());
      continue;
    }
    std::printf("pair: %zu %zu patches %zu %zu in_overlap %d repeated %d repeatability %.3f\n", i, i + skip,
                sa.patches.size(), sb.patches.size(), r.in_overlap, r.repeated, r.fraction());
    sum += r.fraction();
    ++pairs;
  }
  if (pairs == 0)
    throw gasp::Error("no pair of frames with ground truth and patches in their overlap at skip " + std::to_string(skip));
  std::printf("pairs: %d\nmean_repeatability: %.3f\n", pairs, sum / pairs);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"gasp-segment: decompose depth images into regularised surface patches (depth superpixels)"};
  gasp::tools::ParamsOptions params_options;
  gasp::SlamParams all_params;
  if (!params_options.preload(argc, argv, all_params)) return 1;
  gasp::SuperpixelParams& params = all_params.odometry.pair.segment;
  std::string depth_path, tum_dir, intrinsics_arg, out;
  double depth_scale = gasp::kTumDepthUnitsPerMetre, area_cm2 = -1;
  int every = 1, pair_skip = 0;
  auto* depth_opt = app.add_option("--depth", depth_path, "one 16-bit depth PNG");
  auto* tum_opt = app.add_option("--tum", tum_dir, "a TUM RGB-D folder: every frame is segmented");
  depth_opt->excludes(tum_opt);
  bool no_undistort = false;
  app.add_flag("--no-undistort", no_undistort, "resample depth (and rgb) to the pinhole camera when the intrinsics have lens distortion (fr1, fr2: default); this flag uses the images as stored");
  app.add_option("--intrinsics", intrinsics_arg, "fr1|fr2|fr3|ros or an intrinsics file (default: ros for --depth; the folder's for --tum)");
  app.add_option("--depth-scale", depth_scale, "raw depth units per metre")->capture_default_str()->check(gasp::tools::above(0));
  app.add_option("--area-cm2", area_cm2, "target patch area [cm^2] (segment.target_patch_area_m2 in the params file)")
      ->check(gasp::tools::above(0));
  app.add_flag("--step-borders", params.borders.step_borders, "place borders at steps between parallel planes (segment.step_borders; off by default)");
  app.add_option("--every", every, "with --tum: segment every N-th frame")->check(gasp::tools::atLeast(1))->capture_default_str();
  app.add_option("--pairs", pair_skip, "with --tum: measure patch repeatability on pairs (i, i+SKIP) "
                 "of frames with ground truth, i every --every frames, instead of writing pictures")
      ->check(gasp::tools::atLeast(1))
      ->needs(tum_opt);
  app.add_option("--out", out, "picture (PNG) for --depth; output folder for --tum");
  params_options.add(app);
  if (const int code = gasp::tools::parseCommandLine(app, argc, argv); code >= 0) return code;
  if (area_cm2 > 0) params.target_patch_area_m2 = area_cm2 * 1e-4;
  if (const int code = gasp::tools::validOptionValues(all_params); code >= 0) return code;
  if (const int code = params_options.printIfAsked(all_params); code >= 0) return code;
  if (depth_path.empty() && tum_dir.empty()) {
    std::cerr << "error: give --depth FILE.png or --tum DIR\n";
    return 2;
  }
  if (out.empty() && pair_skip == 0) {
    std::cerr << "error: --out is required (except with --pairs)\n";
    return 2;
  }
  if (!depth_path.empty()) {
    try {
      gasp::requireImageWriter(out, "--out picture");  // a usage error, before the work
    } catch (const gasp::Error& e) {
      std::cerr << "error: " << gasp::exceptionMessage(e) << '\n';
      return 2;
    }
  }
  try {
    if (!depth_path.empty()) {
      gasp::tools::RunOutputs outputs({{"--out", out}}, {depth_path});  // before the work, not after it
      auto k = gasp::CameraIntrinsics::fromPresetOrFile(intrinsics_arg.empty() ? "ros" : intrinsics_arg);
      if (no_undistort) k.distortion.fill(0.0);
      const gasp::Undistortion undistortion(k);
      const cv::Mat depth = undistortion.applyToDepth(gasp::loadDepth(depth_path, depth_scale, k.width, k.height));
      k = undistortion.pinhole();
      const auto seg = gasp::segmentDepthSuperpixels(depth, k, params);
      report(seg);
      writePicture(outputs.at("--out"), depth, seg);
      std::printf("picture: %s\n", out.c_str());
      return 0;
    }
    gasp::TumDataset::Options opt;
    if (!intrinsics_arg.empty()) opt.intrinsics = gasp::CameraIntrinsics::fromPresetOrFile(intrinsics_arg);
    opt.undistort = !no_undistort;
    opt.depth_units_per_metre = depth_scale;
    const auto ds = gasp::TumDataset::open(tum_dir, opt);
    if (ds.size() == 0) throw gasp::Error(tum_dir + ": no frames in depth.txt");
    gasp::tools::reportIntrinsics(stdout, ds.intrinsicsSummary(), ds.intrinsicsWarning());
    if (pair_skip > 0) return measurePairs(ds, params, static_cast<std::size_t>(pair_skip), static_cast<std::size_t>(every));
    std::error_code ec;
    std::filesystem::create_directories(out, ec);
    if (ec || !std::filesystem::is_directory(out))
      throw gasp::Error("cannot create the output folder '" + out + "'" + (ec ? ": " + ec.message() : " (a file of that name exists)"));
    const gasp::tools::InputFiles inputs(gasp::tools::tumFolderInputs(tum_dir));
    for (std::size_t i = 0; i < ds.size(); i += static_cast<std::size_t>(every)) {
      const cv::Mat depth = ds.loadDepth(i);
      const auto seg = gasp::segmentDepthSuperpixels(depth, ds.intrinsics(), params);
      std::printf("frame: %zu %.6f\n", i, ds.frame(i).timestamp);
      report(seg);
      char name[64];
      std::snprintf(name, sizeof(name), "/%06zu.png", i);
      gasp::tools::RunOutputs picture({{"--out", out + name}}, inputs);  // never onto one of the folder's images
      writePicture(picture.at("--out"), depth, seg);
    }
    std::printf("pictures: %s\n", out.c_str());
  } catch (const std::exception& e) {  // gasp::Error, and anything a library throws
    std::cerr << "error: " << gasp::exceptionMessage(e) << '\n';
    return 1;
  }
  return 0;
}
