#include "gasp/sim/writer.h"

#include <opencv2/imgcodecs.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <string>

#include "gasp/core/depth_image.h"
#include "gasp/core/error.h"
#include "gasp/core/image_file.h"
#include "gasp/core/output_file.h"

namespace fs = std::filesystem;

namespace gasp::sim {

namespace {

void makeDir(const fs::path& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir))
    throw Error("cannot create output folder '" + dir.string() + "'" +
                (ec ? ": " + ec.message() : std::string(" (a file of that name exists?)")));
}

/// The first line of every depth.txt the simulator writes.
constexpr const char* kDepthListMark = "# depth maps (GASP simulator";

/// A folder that holds a depth.txt the simulator did not write is real data: refused, never
/// overwritten.
void refuseForeignSequence(const fs::path& root) {
  const fs::path depth_list = root / "depth.txt";
  std::error_code ec;
  if (!fs::exists(depth_list, ec)) return;
  std::ifstream in(depth_list);
  std::string first;
  std::getline(in, first);
  if (first.rfind(kDepthListMark, 0) != 0)
    throw Error("output folder '" + root.string() +
                "' holds a depth.txt that gasp-simulate did not write (real data?); write into a new folder");
}

/// A text output of the sequence, written whole or not at all (closeText() commits it).
OutputFile openText(const fs::path& path) {
  OutputFile out(path.string(), "simulated sequence file");
  out.stream() << std::setprecision(9) << std::boolalpha;
  return out;
}

void closeText(OutputFile& out) { out.commit(); }

void writeLabels(const fs::path& path, const cv::Mat& labels) {
  writeImage(path.string(), labels, "label image");
}

void writeSceneInfo(const fs::path& path, const Simulation& sim) {
  const auto& o = sim.options();
  const auto& n = o.noise;
  OutputFile file = openText(path);
  std::ostream& out = file.stream();
  out << "# GASP simulated sequence (gasp-simulate); see docs/simulator.md\n"
      << "scene: " << sim.scene().name << '\n'
      << "description: " << sim.scene().description << '\n'
      << "seed: " << o.seed << '\n'
      << "frames: " << sim.size() << '\n'
      << "start_time_s: " << o.start_time_s << '\n'
      << "rate_hz: " << o.rate_hz << '\n'
      << "occluder: " << (sim.scene().degenerate || !sim.scene().walk.empty() ? "none" : kOccluderName) << '\n';
  for (const ObjectMove& m : o.moves)  // gasp-simulate --move's form
    out << "move: " << m.prefix << ':' << m.shift_m.x() << ',' << m.shift_m.y() << ',' << m.shift_m.z() << ','
        << m.yaw_deg << '@' << m.at_frame << '\n';
  out << "noise.axial_noise: " << n.axial_noise << '\n'
      << "noise.sigma_a_m: " << n.sigma_a_m << '\n'
      << "noise.sigma_b_per_m2: " << n.sigma_b_per_m2 << '\n'
      << "noise.sigma_c_m: " << n.sigma_c_m << '\n'
      << "noise.quantise_disparity: " << n.quantise_disparity << '\n'
      << "noise.baseline_m: " << n.baseline_m << '\n'
      << "noise.disparity_step_px: " << n.disparity_step_px << '\n'
      << "noise.min_range_m: " << n.min_range_m << '\n'
      << "noise.max_range_m: " << n.max_range_m << '\n'
      << "noise.drop_discontinuities: " << n.drop_discontinuities << '\n'
      << "noise.discontinuity_fraction: " << n.discontinuity_fraction << '\n'
      << "noise.drop_grazing: " << n.drop_grazing << '\n'
      << "noise.max_incidence_deg: " << n.max_incidence_deg << '\n'
      << "noise.radial_depth_bias: " << n.radial_depth_bias << '\n'
      << "depth_units_per_metre: " << kTumDepthUnitsPerMetre << '\n';
  closeText(file);
}

}  // namespace

std::string formatTimestamp(double t) {
  std::ostringstream ss;
  ss << std::fixed << std::setprecision(6) << t;
  return ss.str();
}

SimulationSummary writeSimulation(const SimulationOptions& options, const std::string& out_dir) {
  const Simulation sim(options);  // validates everything before touching the disk
  const fs::path root(out_dir);
  refuseForeignSequence(root);
  makeDir(root / "depth");
  makeDir(root / "labels");

  const fs::path depth_list = root / "depth.txt";
  OutputFile depth_file = openText(depth_list);
  std::ostream& depth_txt = depth_file.stream();
  depth_txt << kDepthListMark << ", scene " << sim.scene().name << ", seed " << options.seed
            << ")\n# timestamp filename\n";
  double valid = 0.0, total = 0.0;
  for (int i = 0; i < sim.size(); ++i) {
    const SimulatedFrame f = sim.frame(i);
    const std::string name = formatTimestamp(f.timestamp) + ".png";
    saveDepth((root / "depth" / name).string(), f.depth);
    writeLabels(root / "labels" / name, f.labels);
    depth_txt << formatTimestamp(f.timestamp) << " depth/" << name << '\n';
    valid += static_cast<double>(cv::countNonZero(f.depth));
    total += static_cast<double>(f.depth.total());
  }
  closeText(depth_file);

  writeTumTrajectory((root / "groundtruth.txt").string(), sim.path().poses,
                     "ground truth of the simulated optical camera frame (T_world_camera)");
  options.intrinsics.save((root / "intrinsics.txt").string());

  const fs::path seg_path = root / "segments.txt";
  OutputFile seg_file = openText(seg_path);
  std::ostream& seg = seg_file.stream();
  seg << "# name first_frame last_frame first_timestamp last_timestamp\n";
  for (const auto& s : sim.path().segments)
    seg << s.name << ' ' << s.first_frame << ' ' << s.last_frame << ' '
        << formatTimestamp(sim.path().poses[static_cast<std::size_t>(s.first_frame)].timestamp) << ' '
        << formatTimestamp(sim.path().poses[static_cast<std::size_t>(s.last_frame)].timestamp) << '\n';
  closeText(seg_file);

  const fs::path surf_path = root / "surfaces.txt";
  OutputFile surf_file = openText(surf_path);
  std::ostream& surf = surf_file.stream();
  surf << "# surface_id object shape face (label images hold surface ids; 0 = no surface)\n";
  for (const auto& o : sim.scene().objects)
    for (int face = 0; face < faceCount(o.shape); ++face)
      surf << o.surfaceId(face) << ' ' << o.name << ' ' << shapeTypeName(o.shape) << ' '
           << faceName(o.shape, face) << '\n';
  closeText(surf_file);

  writeSceneInfo(root / "scene.txt", sim);

  SimulationSummary summary;
  summary.out_dir = out_dir;
  summary.scene = sim.scene().name;
  summary.frames = sim.size();
  summary.seed = options.seed;
  summary.valid_pixel_share = total > 0.0 ? valid / total : 0.0;
  summary.segments = sim.path().segments;
  return summary;
}

}  // namespace gasp::sim
