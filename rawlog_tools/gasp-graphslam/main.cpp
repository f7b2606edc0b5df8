// gasp-graphslam: MRPT's graph-SLAM engine (mrpt::graphslam::CGraphSlamEngine, 3D graphs) over a
// rawlog of depth scans, with GASP's node and edge registration deciders and optimiser, or any
// MRPT ones the options checker knows (gasp/graphslam/options_checker.h).
//   gasp-graphslam --rawlog FILE [--ini FILE] [--node-reg NAME] [--edge-reg NAME] [--optimizer NAME]
//                  [--out TRAJ.txt] [--graph G.graph] [--report-dir DIR] [--gt TRAJ.txt]
//                  [--simplemap MAP.simplemap] [--cloud MAP.ply] [--voxel 0.01] [--cloud-max-depth 4]
//                  [--params FILE]
//   gasp-graphslam --list-regs | --list-optimizers | --print-ini | [--params FILE] [--ini FILE] --print-params
// --params FILE: a params file (docs/parameters.md) whose values GASP's deciders and optimiser
// take, --ini's keys over them; --print-params prints what they would read.
// Runs without a window. After the last step the graph is optimised once more (CGaspPoseGraphGSO),
// because the engine re-derives node poses along a spanning tree at every node it registers.
// Exit codes: 0 done, 1 bad input, 2 usage error, 3 written, but GASP's odometry lost track
// (break edges in the graph).
#include <CLI/CLI.hpp>
#include <mrpt/config/CConfigFile.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/io/lazy_load_path.h>
#include <mrpt/system/filesystem.h>

#include <stdlib.h>  // mkstemps
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "default_ini.h"
#include "gasp/core/error.h"
#include "gasp/core/tum_trajectory.h"
#include "gasp/graphslam/CGaspLoopClosureERD.h"
#include "gasp/graphslam/CGaspOdometryNRD.h"
#include "gasp/graphslam/CGaspPoseGraphGSO.h"
#include "gasp/graphslam/engine.h"
#include "gasp/graphslam/graph_marginals.h"
#include "gasp/graphslam/ini_check.h"
#include "gasp/graphslam/options_checker.h"
#include "gasp/graphslam/rawlog_run.h"
#include "gasp/graphslam/scan_selection.h"
#include "gasp/params/params_io.h"
#include "gasp/rawlog/rawlog_entries.h"
#include "gasp/rawlog/rawlog_format.h"
#include "cli.h"
#include "params_options.h"
#include "map_output.h"
#include "marginals_report.h"
#include "sequence_report.h"

namespace {

using gasp::graphslam::Graph3D;

/// The configuration the engine reads: the built-in one, the params file's values (--params)
/// over it in the deciders' and optimiser's sections, and the user's --ini (if any) over both, key
/// by key, so that a file with a few keys keeps the values of everything else (MRPT's engine
/// asserts on missing sections such as [GeneralConfiguration]).
mrpt::config::CConfigFileMemory mergedIni(const std::string& user_ini, const gasp::SlamParams* params) {
  mrpt::config::CConfigFileMemory merged(std::string(gasp::tools::kDefaultGraphSlamIni));
  if (params) {
    gasp::writeOdometryParams(params->odometry, merged, "CGaspOdometryNRD");
    gasp::writeLoopClosureParams(params->odometry.pair, params->loop, merged, "CGaspLoopClosureERD");
    gasp::writePoseGraphSettings(params->graph, merged, "CGaspPoseGraphGSO");
  }
  if (!user_ini.empty()) {
    const mrpt::config::CConfigFile user(user_ini);
    std::vector<std::string> sections, keys;
    user.getAllSections(sections);
    for (const auto& section : sections) {
      user.getAllKeys(section, keys);
      for (const auto& key : keys) merged.write(section, key, user.read_string(section, key, ""));
    }
  }
  return merged;
}

/// The parameters GASP's deciders and optimiser read from `ini` (what --print-params prints): the
/// node decider's pair and odometry keys, the loop closer's own keys, the optimiser's.
gasp::SlamParams paramsOfIni(const mrpt::config::CConfigFileBase& ini) {
  gasp::SlamParams p;
  gasp::readOdometryParams(ini, "CGaspOdometryNRD", p.odometry, {"sensor_label", "class_verbosity"});
  gasp::PairParams loop_pair = p.odometry.pair;
  gasp::readLoopClosureParams(ini, "CGaspLoopClosureERD", loop_pair, p.loop, {"sensor_label", "class_verbosity"});
  gasp::readPoseGraphSettings(ini, "CGaspPoseGraphGSO", p.graph, {"drop_chi2", "class_verbosity"});
  gasp::SlamParams with_loop_pair = p;
  with_loop_pair.odometry.pair = loop_pair;
  if (!gasp::sameParams(with_loop_pair, p))
    std::fprintf(stderr, "warning: [CGaspLoopClosureERD] sets pair keys other than [CGaspOdometryNRD]'s; the params "
                         "printed are the node decider's\n");
  return p;
}

/// The merged configuration in a temporary file of its own (mkstemps) that lives only while the
/// engine is made (the engine and the deciders read it in the engine's constructor).
class TemporaryIni {
 public:
  explicit TemporaryIni(const mrpt::config::CConfigFileMemory& merged) {
    std::string text;
    merged.getContent(text);
    const std::string dir = std::filesystem::temp_directory_path().string();
    path_ = dir + "/gasp-graphslam-XXXXXX.ini";
    const int fd = ::mkstemps(path_.data(), 4);
    if (fd < 0) {
      const int error = errno;
      throw gasp::Error("cannot create a temporary configuration file in " + dir + ": " + std::strerror(error));
    }
    std::size_t written = 0;
    int error = 0;
    while (written < text.size()) {
      const ssize_t w = ::write(fd, text.data() + written, text.size() - written);
      if (w < 0 && errno == EINTR) continue;
      if (w <= 0) {
        error = w < 0 ? errno : EIO;
        break;
      }
      written += static_cast<std::size_t>(w);
    }
    if (::close(fd) != 0 && error == 0) error = errno;
    if (written < text.size() || error != 0) {
      std::error_code ec;
      std::filesystem::remove(path_, ec);
      throw gasp::Error("cannot write the configuration to " + path_ + ": " + std::strerror(error));
    }
  }
  ~TemporaryIni() {
    std::error_code ec;
    std::filesystem::remove(path_, ec);
  }
  TemporaryIni(const TemporaryIni&) = delete;
  TemporaryIni& operator=(const TemporaryIni&) = delete;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"gasp-graphslam: MRPT's graph-SLAM engine (3D) over a rawlog of depth scans with GASP's node and "
               "edge registration deciders and optimiser"};
  std::string rawlog_path, ini_path, out_path, graph_path, report_dir, gt_path;
  gasp::tools::MapOutputOptions map_output;
  std::string node_reg = "CGaspOdometryNRD", edge_reg = "CGaspLoopClosureERD", optimizer = "CGaspPoseGraphGSO";
  bool list_regs = false, list_optimizers = false, print_ini = false;
  app.add_option("--rawlog", rawlog_path, "MRPT rawlog with CObservation3DRangeScan (format #1 or #2)");
  app.add_option("--ini", ini_path, "configuration (default: the built-in one, see --print-ini)");
  app.add_option("--node-reg", node_reg, "node registration decider (--list-regs)")->capture_default_str();
  app.add_option("--edge-reg", edge_reg, "edge registration decider (--list-regs)")->capture_default_str();
  app.add_option("--optimizer", optimizer, "graph optimiser (--list-optimizers)")->capture_default_str();
  app.add_option("--out", out_path, "the nodes' depth-camera trajectory (TUM format, world = the first node's robot frame)");
  app.add_option("--graph", graph_path, "the graph (MRPT VERTEX3/EDGE3, robot frames)");
  app.add_option("--report-dir", report_dir, "directory for the engine's reports (MRPT's .log files: classes, timings)");
  app.add_option("--gt", gt_path, "ground truth (TUM format) to evaluate the nodes' trajectory against");
  gasp::graphslam::ScanSelection selection;
  app.add_option("--first", selection.first,
                 "first scan used (index among the deciders' sensor's scans; the steps before it still give their odometry)")
      ->capture_default_str()
      ->check(gasp::tools::atLeast(0));
  app.add_option("--every", selection.every, "use every N-th scan from --first on (a wider baseline between scans)")
      ->capture_default_str()
      ->check(gasp::tools::atLeast(1));
  app.add_option("--max-scans", selection.max_scans, "stop after this many used scans (0 = the whole rawlog)")
      ->capture_default_str()
      ->check(gasp::tools::atLeast(0));
  gasp::tools::addMapOutputOptions(app, map_output, "nodes");
  app.add_flag("--list-regs", list_regs, "list the node and edge registration deciders for 3D graphs");
  app.add_flag("--list-optimizers", list_optimizers, "list the optimisers");
  app.add_flag("--print-ini", print_ini, "print the default configuration");
  gasp::tools::ParamsOptions params_options;
  gasp::SlamParams params;
  if (!params_options.preload(argc, argv, params)) return 1;
  params_options.add(app);  // the file's values go into the deciders' sections, --ini's keys over them
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return gasp::tools::usageExit(app, e);  // --help: 0; any usage error: 2
  }
  const gasp::SlamParams* params_file = params_options.file().empty() ? nullptr : &params;

  gasp::graphslam::GaspOptionsChecker checker;
  if (print_ini) std::cout << gasp::tools::kDefaultGraphSlamIni;
  if (list_regs) checker.dumpRegistrarsToConsole("all");
  if (list_optimizers) checker.dumpOptimizersToConsole();
  if (print_ini || list_regs || list_optimizers) return 0;
  if (params_options.printing()) {
    try {
      if (!ini_path.empty()) {
        const auto check = gasp::graphslam::checkGraphSlamIni(ini_path);
        if (!check.error.empty()) throw gasp::Error(check.error);
      }
      return params_options.printIfAsked(paramsOfIni(mergedIni(ini_path, params_file)));
    } catch (const std::exception& e) {
      std::cerr << "error: " << gasp::exceptionMessage(e) << '\n';
      return 1;
    }
  }
  if (rawlog_path.empty()) {
    std::cerr << "error: give --rawlog FILE\n";
    return 2;
  }
  if (!checker.checkRegistrationDeciderExists(node_reg, "node") || !checker.node_regs_map.count(node_reg)) {
    std::cerr << "error: no node registration decider '" << node_reg << "' for 3D graphs (see --list-regs)\n";
    return 2;
  }
  if (!checker.checkRegistrationDeciderExists(edge_reg, "edge") || !checker.edge_regs_map.count(edge_reg)) {
    std::cerr << "error: no edge registration decider '" << edge_reg << "' for 3D graphs (see --list-regs)\n";
    return 2;
  }
  if (!checker.checkOptimizerExists(optimizer) || !checker.optimizers_map.count(optimizer)) {
    std::cerr << "error: no optimiser '" << optimizer << "' for 3D graphs (see --list-optimizers)\n";
    return 2;
  }

  try {
    if (!mrpt::system::fileExists(rawlog_path)) throw gasp::Error("cannot open rawlog " + rawlog_path);
    std::vector<std::string> inputs = gasp::tools::rawlogInputs(rawlog_path);
    for (const std::string& f : {gt_path, ini_path})
      if (!f.empty()) inputs.push_back(f);
    std::vector<std::pair<std::string, std::string>> output_paths{{"--out", out_path}, {"--graph", graph_path}};
    for (const auto& p : gasp::tools::mapOutputPaths(map_output)) output_paths.push_back(p);
    gasp::tools::RunOutputs outputs(output_paths, inputs);  // before the run, not after it
    if (!ini_path.empty() && !mrpt::system::fileExists(ini_path)) throw gasp::Error("cannot open configuration " + ini_path);
    if (!ini_path.empty()) {
      if (std::filesystem::is_directory(ini_path)) throw gasp::Error("configuration " + ini_path + " is a folder");
      // MRPT's reader passes over malformed lines and unread sections silently.
      const auto check = gasp::graphslam::checkGraphSlamIni(ini_path);
      if (!check.error.empty()) throw gasp::Error(check.error);
      for (const auto& s : check.unknown_sections)
        std::fprintf(stderr, "warning: %s: section [%s] is read by no decider (misspelt?); its keys are ignored\n",
                     ini_path.c_str(), s.c_str());
    }
    const gasp::Trajectory gt = gt_path.empty() ? gasp::Trajectory{} : gasp::readTumTrajectory(gt_path);
    // MRPT's engine and deciders log to stdout: sent to stderr until the engine is gone, so that
    // stdout holds only this program's "key: value" lines.
    std::optional<gasp::graphslam::StdoutToStderr> mrpt_log_to_stderr(std::in_place);
    // The checker's factories return new objects; the engine does not own them.
    std::unique_ptr<mrpt::graphslam::deciders::CNodeRegistrationDecider<Graph3D>> nrd(checker.node_regs_map[node_reg]());
    std::unique_ptr<mrpt::graphslam::deciders::CEdgeRegistrationDecider<Graph3D>> erd(checker.edge_regs_map[edge_reg]());
    std::unique_ptr<mrpt::graphslam::optimizers::CGraphSlamOptimizer<Graph3D>> gso(checker.optimizers_map[optimizer]());
    auto* gasp_nrd = dynamic_cast<gasp::graphslam::CGaspOdometryNRD*>(nrd.get());
    auto* gasp_erd = dynamic_cast<gasp::graphslam::CGaspLoopClosureERD*>(erd.get());
    auto* gasp_gso = dynamic_cast<gasp::graphslam::CGaspPoseGraphGSO*>(gso.get());
    auto engine = [&] {
      const TemporaryIni engine_ini(mergedIni(ini_path, params_file));  // built-in < --params < --ini
      return gasp::graphslam::makeGraphSlamEngine(engine_ini.path(), rawlog_path, *nrd, *erd, *gso);
    }();

    // GASP's optimiser tells GASP's loop closer at once when it removes an edge, so that the rest
    // of a relocalisation group leaves the graph before the next optimisation.
    if (gasp_gso && gasp_erd) gasp_gso->setAfterEdgeRemoval([gasp_erd] { return gasp_erd->syncWithGraph(); });
    // The loop closer takes each node's view from GASP's node decider (no second segmentation).
    if (gasp_erd && gasp_nrd) gasp_erd->useKeyframeViewsOf(gasp_nrd);
    if (optimizer == "CLevMarqGSO")
      std::fprintf(stderr, "warning: MRPT 2.5.8's CLevMarqGSO applies an edge's information to [x y z rx ry rz], not to "
                           "[x y z yaw pitch roll] as CPose3DPDFGaussianInf declares it (docs/graphslam.md)\n");
    // Images stored outside the rawlog (<rawlog>_Images/) are found as MRPT's tools find them.
    mrpt::io::setLazyLoadPathBase(gasp::findRawlogImagesDirectory(rawlog_path));
    gasp::RawlogEntries entries(rawlog_path);  // a truncated or corrupt file is an error, not an early end
    // The scans the deciders use (their sensor_label; GASP's node decider's first).
    const std::string sensor_label = gasp_nrd ? gasp_nrd->sensorLabel() : (gasp_erd ? gasp_erd->sensorLabel() : "");
    gasp::graphslam::RawlogRunOptions run_options;
    run_options.selection = selection;
    run_options.keep_depth = map_output.wanted();
    gasp::graphslam::RawlogRunResult run =
        gasp::graphslam::runOverRawlog(*engine, entries, sensor_label, gasp_nrd, run_options);
    const std::string of_sensor = sensor_label.empty() ? std::string() : " with sensorLabel '" + sensor_label + "'";
    if (run.seen_scans == 0) throw gasp::Error(rawlog_path + ": no CObservation3DRangeScan in the rawlog" + of_sensor);
    if (run.scans == 0)
      throw gasp::Error(rawlog_path + ": --first " + std::to_string(selection.first) + " is beyond its " +
                        std::to_string(run.seen_scans) + " scans" + of_sensor);

    gasp::graphslam::finishGraph(gasp_gso, gasp_erd);  // optimised, the closures it removed forgotten
    if (engine->getGraph().nodeCount() == 0)
      throw gasp::Error(rawlog_path + ": no graph: fewer than two nodes were registered (" + std::to_string(run.scans) +
                        " scans; with CGaspOdometryNRD, fewer than two keyframes)");
    gasp::Trajectory trajectory;
    gasp::PoseGraphMarginals marginals;  // the nodes' uncertainty in the optimised graph
    std::size_t node_count = 0, edge_count = 0;
    {  // the graph's outputs, while the engine lives
      const Graph3D& graph = engine->getGraph();
      trajectory = gasp::graphslam::nodeTrajectory(graph, run.nodes);
      try {
        marginals = gasp::graphslam::graphMarginals(graph);
      } catch (const gasp::Error& e) {  // no covariance, but the outputs are still written
        marginals.message = e.what();
      }

      if (auto* out = outputs.find("--out")) {
        gasp::tools::SequenceEnd end;
        end.complete = run.complete;
        end.error = run.input_error;
        end.frames = run.scans;
        gasp::writeTumTrajectory(out->stream(), trajectory,
                                 gasp::tools::trajectoryHeader("node (keyframe) depth-camera trajectory by gasp-graphslam", end));
        out->commit();
      }
      if (auto* graph_file = outputs.find("--graph")) {
        // The engine's graph as it is, except that an edge with non-finite information (MRPT's
        // CFixedIntervalsNRD gives its first edge NaN) is written as a break edge: a file of
        // `nan` information matrices is no graph another tool can read.
        Graph3D written = graph;
        if (const std::size_t broken = gasp::graphslam::breakNonFiniteEdges(written))
          std::fprintf(stderr, "warning: %zu edge(s) with non-finite information from the node decider written as break edges (information %g)\n",
                       broken, gasp::graphslam::kBreakInformation);
        gasp::tools::writeGraph(*graph_file, written);
      }
      if (!report_dir.empty()) {
        std::filesystem::create_directories(report_dir);
        engine->generateReportFiles(report_dir);
      }
      node_count = graph.nodeCount();
      edge_count = graph.edgeCount();
    }
    engine.reset();  // its time logger's table goes to stderr too
    mrpt_log_to_stderr.reset();
    std::vector<gasp::RgbdFrame> map_frames;  // for --simplemap and --cloud: nodes with a converted scan
    std::vector<gasp::Isometry3> map_poses;
    std::vector<gasp::Matrix6> map_covariances;  // a node no edge reaches is its own piece: zero
    for (std::size_t i = 0; i < run.nodes.size() && run_options.keep_depth; ++i) {
      if (!run.nodes[i].frame) continue;
      map_poses.push_back(trajectory[i].T_world_camera);
      map_frames.push_back(std::move(*run.nodes[i].frame));
      if (marginals.computed) map_covariances.push_back(marginals.covariance[i].value_or(gasp::Matrix6::Zero()));
    }
    if (!marginals.computed && !map_output.simplemap_path.empty())
      std::fprintf(stderr, "warning: the simple map's poses carry a zero covariance: %s\n", marginals.message.c_str());
    if (marginals.computed && !map_output.simplemap_path.empty() && gasp_nrd && gasp_nrd->breakEdges() > 0)
      std::fprintf(stderr, "warning: the graph has %zu break edge(s): a simple-map pose's covariance is relative to the "
                           "first node of its piece, and the pieces are placed only by the odometry's prediction\n",
                   gasp_nrd->breakEdges());
    if (run_options.keep_depth && map_frames.size() < run.nodes.size())
      std::fprintf(stderr, "warning: %zu of %zu nodes have no depth scan that could be converted; the map leaves them out\n",
                   run.nodes.size() - map_frames.size(), run.nodes.size());
    gasp::tools::writeMapOutputs(map_output, outputs, map_frames, map_poses, "nodes", map_covariances);

    std::printf("rawlog_entries: %zu\n", run.steps);
    std::printf("scans: %zu\n", run.scans);
    if (run.seen_scans > run.scans)
      std::printf("scans_not_used: %zu (--first, --every, --max-scans)\n", run.seen_scans - run.scans);
    std::printf("deciders: %s, %s, %s\n", node_reg.c_str(), edge_reg.c_str(), optimizer.c_str());
    std::printf("nodes: %zu\n", node_count);
    std::printf("edges: %zu\n", edge_count);
    if (gasp_nrd) {
      std::printf("break_edges: %zu\n", gasp_nrd->breakEdges());
      if (gasp_nrd->skippedScans() > 0) {
        std::printf("skipped_scans: %zu\n", gasp_nrd->skippedScans());
        std::fprintf(stderr, "warning: %zu scans could not be converted and were skipped (see the warnings above)\n",
                     gasp_nrd->skippedScans());
      }
    }
    if (gasp_erd) {
      std::size_t relocalisations = 0, tried = 0;
      for (const auto& a : gasp_erd->attempts()) {
        relocalisations += a.accepted && a.relocalisation ? 1 : 0;
        tried += a.relocalisation ? 0 : 1;
      }
      std::printf("loop_closures: %zu (%zu registrations tried; %zu relocalisations)\n",
                  gasp_erd->insertedEdges() - relocalisations, tried, relocalisations);
    }
    if (gasp_gso)
      std::printf("optimisations: %zu (%.1f ms in all; %zu loop closures removed)\n", gasp_gso->optimisations(),
                  gasp_gso->optimisationMs(), gasp_gso->droppedEdges());
    if (!out_path.empty()) std::printf("trajectory: %s\n", out_path.c_str());
    if (!graph_path.empty()) std::printf("graph: %s\n", graph_path.c_str());
    gasp::tools::printEvaluation(gt, trajectory, trajectory.size());  // every node is a registered scan
    gasp::tools::printMarginals(marginals, trajectory, gt, "node");
    if (!run.complete) {
      std::printf("partial: %zu scans (the rawlog ended with an error); the outputs hold these scans only\n", run.scans);
      std::fprintf(stderr, "error: %s\n", run.input_error.c_str());
      return 1;
    }
    if (gasp_nrd && (gasp_nrd->breakEdges() > 0 || gasp_nrd->skippedScans() > 0)) return 3;
  } catch (const std::exception& e) {  // gasp::Error, MRPT's (configuration, rawlog), filesystem
    std::cerr << "error: " << gasp::exceptionMessage(e) << '\n';
    return 1;
  }
  return 0;
}
