// gasp-slam: a map built offline from a depth sequence with GASP: odometry, loop closures and the
// optimised pose graph (gasp/slam/depth_slam.h).
//   gasp-slam --tum DIR | --rawlog FILE | --session PATH[@FIRST-LAST]... [--sensor LABEL]
//             [--gt TRAJ.txt] --out TRAJ.txt [--graph G.graph] [--simplemap MAP.simplemap]
//             [--cloud MAP.ply] [--marginals-csv M.csv] [--sessions-report R.yaml]
//             [--params FILE] [--checkpoint FILE [--resume]] [--mpi] [options]
// Writes the optimised trajectory of the depth camera (TUM format) in the world of the first
// frame's robot frame (MRPT's sensorPose; TUM folders: the camera looking along the robot's +X;
// a rawlog of LiDAR sweeps: the LiDAR's, with the params' lidar section, lidarSlamParams()),
// optionally the pose graph with its loop closures (MRPT VERTEX3 / EDGE3), the keyframes as an
// MRPT simple map (for MRPT's observations2map; each pose with its marginal covariance in the
// graph) and a voxel point map (PLY).
// Several sessions (--session, repeated: recordings with no known relation) are tracked one after
// the other, each on its own, and joined where relocalisation finds agreeing constraints between
// them (never otherwise): one trajectory per session (TRAJ.session<N>.txt) in its map's world,
// one graph and map over all, and the report of which sessions were joined.
// Every output is opened before the run and written whole or not at all (run_outputs.h).
// --checkpoint journals the loop searches' registrations as they are made
// (gasp/slam/registration_log.h); a run cut short and started again with --resume answers from it
// what it had registered and registers only the rest: with the searches in place
// (loop_closure.background: false), the same graph as the uninterrupted run.
// --mpi (mpirun -np N gasp-slam ... --mpi; built with GASP_WITH_MPI): rank 0 runs the job and
// hands its loop registrations to the other ranks (gasp/mpi/registrar_pool.h).
// Exit codes: 0 every frame tracked and the graph in one piece, 1 bad input (when the input ends
// with an error after some frames, the outputs are written for those frames, marked partial),
// 2 usage error, 3 written, but some frames were not tracked or the graph stayed in pieces.
#include <CLI/CLI.hpp>

#include <cmath>
#include <filesystem>
#include <chrono>
#include <cstdio>
#include <ostream>
#include <iostream>
#include <optional>
#include <vector>

#include "gasp/core/error.h"
#include "gasp/core/format.h"
#include "gasp/core/output_file.h"
#include "gasp/core/stopwatch.h"
#include "gasp/core/tum_trajectory.h"
#include "gasp/mrpt/keyframe_map.h"
#include "gasp/mrpt/pose_graph.h"
#include "gasp/rawlog/depth_sequence.h"
#include "gasp/slam/depth_slam.h"
#include "gasp/slam/point_map.h"
#include "gasp/slam/registration_log.h"
#include "cli.h"
#include "params_options.h"
#include "frames_ahead.h"
#include "map_output.h"
#include "run_outputs.h"
#include "marginals_report.h"
#include "sequence_options.h"
#include "sequence_report.h"
#include "sessions.h"
#ifdef GASP_WITH_MPI
#include "gasp/mpi/registrar_pool.h"
#include "handed_frames.h"
#endif

namespace {

constexpr const char* kOtherMounting =
    "its depth camera sits on the robot (sensorPose) otherwise than the first session's: the sessions of one map must "
    "share one camera mounting";

/// `frame` added to `tracker` (DepthOdometry or DepthSlam): a sweep, or a depth image.
template <class Tracker>
const gasp::OdometryFrame& addTo(Tracker& tracker, const gasp::RgbdFrame& frame,
                                 std::optional<gasp::SegmentedDepth> segmented) {
  return frame.isSweep() ? tracker.addFrame(frame.timestamp, *frame.sweep, std::move(segmented))
                         : tracker.addFrame(frame.timestamp, frame.depth_m, frame.depth_intrinsics, std::move(segmented));
}

/// A keyframe as the map outputs keep it: depth only; deskewed as it was registered (keyframe_map.h).
gasp::RgbdFrame mapKeyframe(const gasp::RgbdFrame& frame, const gasp::OdometryFrame& f, const gasp::DepthView* view) {
  gasp::RgbdFrame kept = frame;
  kept.rgb.release();
  return f.deskewed && view ? gasp::withViewDepth(std::move(kept), *view) : kept;
}

#ifdef GASP_WITH_MPI
/// --mpi, a rank other than 0: tracks one session (`options`) as rank 0 would, from the first
/// session's mounting that rank 0's `context` gives, and hands each frame to `emit`; returns the
/// session's end (handed_frames.h). An input this rank cannot open is the job's error (thrown).
std::string trackForRankZero(const gasp::DepthSequenceOptions& options, const std::string& context,
                             gasp::SlamParams params, bool sequential, bool keep_keyframes,
                             const std::function<void(std::string)>& emit) {
  gasp::ByteReader r(context, "MPI: rank 0's context");
  const bool sweeps = r.getFlag("the sensor");
  const gasp::Isometry3 T_robot_camera = r.getPose("the first session's mounting");
  if (sweeps) params = gasp::lidarSlamParams(params);
  gasp::DepthSequence sequence(options);
  gasp::tools::HandedEnd end;
  std::optional<gasp::DepthOdometry> odometry;  // made once a frame passes the mounting check
  try {
    end.end = gasp::tools::forEachFrameWithViewAhead(sequence, params.odometry, sequential, [&](const gasp::RgbdFrame& frame, auto segmented) {
      if (!odometry) {
        if (!frame.T_robot_camera.isApprox(T_robot_camera, 1e-9)) throw gasp::Error(kOtherMounting);
        odometry.emplace(params.odometry, T_robot_camera);
      }
      const gasp::OdometryFrame& f = addTo(*odometry, frame, std::move(segmented));
      std::optional<gasp::RgbdFrame> kept;
      if (f.keyframe && keep_keyframes) kept = mapKeyframe(frame, f, odometry->keyframeView());
      emit(gasp::tools::handedFrameBytes(odometry->lastTracked(), kept ? &*kept : nullptr));
    });
  } catch (const gasp::Error& e) {  // the session's error, as one process reports it
    end.threw = true;
    end.end.error = e.what();
  }
  end.reached = odometry.has_value();
  return gasp::tools::handedEndBytes(end);
}
#endif

void writeLoopsCsv(std::ostream& out, const std::vector<gasp::LoopClosureAttempt>& attempts) {
  out << "from,to,relocalisation,accepted,inliers,gate_chi2,registration_ms,reason\n";
  for (const auto& a : attempts) {
    std::string reason = a.reason;
    for (char& c : reason) c = c == '"' ? '\'' : c;
    char buf[200];
    std::snprintf(buf, sizeof buf, "%zu,%zu,%d,%d,%d,%.3f,%.2f,", a.from, a.to, a.relocalisation ? 1 : 0,
                  a.accepted ? 1 : 0, a.inliers, a.gate_chi2, a.registration_ms);
    out << buf << '"' << reason << "\"\n";
  }
}

/// What names a session's frames for a registration journal's fingerprint: every input option and
/// each of its input files' (`files`) size and modification time (a file replaced, another
/// camera: another job).
std::string sessionFingerprint(const gasp::DepthSequenceOptions& o, const std::vector<std::string>& files) {
  std::string text = "tum " + o.tum_dir + " rawlog " + o.rawlog_path + " sweeps " + std::to_string(o.sweeps) +
                     " sensor " + o.sensor_label + " first " + std::to_string(o.first) + " every " +
                     std::to_string(o.every) + " max " + std::to_string(o.max_frames) + " intrinsics " + o.intrinsics +
                     " units " + gasp::formatted("%.17g", o.depth_units_per_metre) + " undistort " +
                     std::to_string(o.undistort);
  for (const std::string& f : files) {
    std::error_code e1, e2;
    const auto size = std::filesystem::file_size(f, e1);
    const auto time = std::filesystem::last_write_time(f, e2);
    text += " file " + f + " " + (e1 ? "?" : std::to_string(size)) + " " +
            (e2 ? "?" : std::to_string(time.time_since_epoch().count()));
  }
  return text;
}

/// The registration journal is neither an input nor another output, and a journal already there
/// is continued only with --resume (a restart without it would drop the checkpoint).
void checkJournalPath(const std::string& path, bool resume, const gasp::tools::InputFiles& inputs,
                      const std::vector<std::pair<std::string, std::string>>& outputs) {
  namespace fs = std::filesystem;
  const gasp::FileIdentity journal = gasp::fileIdentity(path);
  if (const std::string* input = journal.exists() ? inputs.find(journal) : nullptr)
    throw gasp::Error("--checkpoint '" + path + "' is the input '" + *input + "'");
  std::error_code ec;
  const fs::path canonical = fs::weakly_canonical(path, ec);
  for (const auto& [option, output] : outputs)
    if (!output.empty() && fs::weakly_canonical(output, ec) == canonical)
      throw gasp::Error("--checkpoint '" + path + "' is also the output of " + option);
  if (!resume && journal.exists() && gasp::RegistrationLog::isJournal(path))
    throw gasp::Error("--checkpoint '" + path + "' holds a registration journal: add --resume to go on from it, or " +
                      "remove it to start again");
}

}  // namespace

int main(int argc, char** argv) {
  bool use_mpi = false;
  for (int i = 1; i < argc; ++i) use_mpi = use_mpi || std::string(argv[i]) == "--mpi";
#ifdef GASP_WITH_MPI
  std::optional<gasp::mpi::Session> mpi;
  try {
    if (use_mpi) mpi.emplace(argc, argv);
  } catch (const gasp::Error& e) {
    std::cerr << "error: " << e.what() << '\n';
    return 1;
  }
#else
  if (use_mpi) {
    std::cerr << "error: --mpi: this gasp-slam was built without MPI (cmake -DGASP_WITH_MPI=ON, with libopenmpi-dev)\n";
    return 2;
  }
#endif
  CLI::App app{"gasp-slam: a map built offline from a depth sequence with GASP: odometry, loop closures between "
               "keyframes and the optimised pose graph"};
  gasp::DepthSequenceOptions input;
  std::string gt_path, out_path, odometry_out, graph_path, frames_csv, loops_csv, marginals_csv;
  gasp::tools::MapOutputOptions map_output;
  bool no_loops = false;
  gasp::tools::ParamsOptions params_options;
  gasp::SlamParams params;
  if (!params_options.preload(argc, argv, params)) return 1;
  gasp::tools::addSequenceOptions(app, input, gt_path, true);
  std::vector<std::string> session_specs;
  std::string sessions_report;
  auto* sessions_option = app.add_option(
      "--session", session_specs,
      "one session: a TUM folder or a rawlog, optionally its frames FIRST-LAST (PATH@FIRST-LAST); repeat for several "
      "sessions, tracked each on its own and joined into one map where they share places (--every, --sensor, "
      "--intrinsics, --depth-scale apply to all)");
  for (const char* single : {"--tum", "--rawlog", "--gt", "--first", "--max-frames"})
    sessions_option->excludes(app.get_option(single));
  app.add_option("--sessions-report", sessions_report,
                 "the sessions' report to write (YAML: each session's frames, map, links to the others and ATE)");
  app.add_option("--out", out_path, "optimised trajectory to write (TUM format: timestamp tx ty tz qx qy qz qw of the depth camera; required)");
  app.add_option("--odometry-out", odometry_out, "the odometry's trajectory before loop closures (TUM format, same world)");
  app.add_option("--graph", graph_path, "pose graph to write: odometry and loop-closure edges at the optimised poses (MRPT VERTEX3/EDGE3, robot frames)");
  gasp::tools::addMapOutputOptions(app, map_output, "keyframes");
  app.add_option("--frames-csv", frames_csv, "one line per frame: tracked, keyframe, reference, patches, inliers, times, reason");
  app.add_option("--loops-csv", loops_csv, "one line per loop-closure registration: keyframes, accepted, inliers, gate chi-square, reason");
  app.add_option("--marginals-csv", marginals_csv,
                 "one line per constrained frame: its pose's marginal covariance in the optimised graph "
                 "(left perturbation [t r] in the world, relative to the first frame of its piece)");
  gasp::tools::addOdometryOptions(app, params.odometry);
  bool sequential = false;
  gasp::tools::addSequentialOption(app, sequential);
  app.add_flag("--no-loop-closures", no_loops,
               "odometry only (no loop closures, no optimisation; loop_closure.enabled = false)");
  std::string checkpoint_path;
  bool resume = false;
  app.add_option("--checkpoint", checkpoint_path,
                 "journal of the loop searches' registrations, appended and flushed as they are made: a run cut short "
                 "resumes from it with --resume (with loop_closure.background: false, the same graph as the "
                 "uninterrupted run)");
  app.add_flag("--resume", resume,
               "answer from the --checkpoint journal (the same inputs and parameters) what it holds, register the rest "
               "and go on journaling")
      ->needs(app.get_option("--checkpoint"));
  app.add_flag("--mpi", use_mpi,
               "under mpirun: rank 0 runs the job and hands its loop registrations to the other ranks, each a keyframe's "
               "view sent once (with loop_closure.background: false, the single process's graph)");
  params_options.add(app);
  if (const int code = gasp::tools::parseCommandLine(app, argc, argv); code >= 0) return code;
  if (no_loops) params.loop.enabled = false;
  if (const int code = gasp::tools::validOptionValues(params); code >= 0) return code;
  if (const int code = params_options.printIfAsked(params); code >= 0) return code;
  if (input.tum_dir.empty() && input.rawlog_path.empty() && session_specs.empty()) {
    std::cerr << "error: give --tum DIR, --rawlog FILE or --session PATH\n";
    return 2;
  }
  if (out_path.empty()) {
    std::cerr << "error: --out is required\nRun with --help for more information.\n";
    return 2;
  }

#ifdef GASP_WITH_MPI
  if (mpi && mpi->rank() != 0) {  // a worker: tracks its sessions, registers the pairs rank 0 hands it, writes nothing
    try {
      gasp::validate(params);
      std::vector<gasp::DepthSequenceOptions> sessions;
      for (const std::string& spec : session_specs) sessions.push_back(gasp::tools::sessionOptions(spec, input));
      if (sessions.empty()) sessions.push_back(input);
      const auto track = [&](std::size_t s, const std::string& context, const std::function<void(std::string)>& emit) {
        if (s >= sessions.size()) throw gasp::Error("MPI: rank 0 asks for session " + std::to_string(s + 1) + " of " + std::to_string(sessions.size()));
        return trackForRankZero(sessions[s], context, params, sequential, map_output.wanted(), emit);
      };
      gasp::mpi::serveRegistrations(*mpi, gasp::paramsYaml(params), params,
                                    gasp::paramsYaml(gasp::lidarSlamParams(params)), gasp::lidarSlamParams(params), track);
    } catch (const std::exception& e) {  // rank 0 would wait for this rank for ever: the job ends
      std::cerr << "error: rank " << mpi->rank() << ": " << gasp::exceptionMessage(e) << std::endl;
      mpi->abort(1);
    }
    return 0;
  }
#endif
  try {
    gasp::validate(params);
    const gasp::VoxelPointMap probe(map_output.voxel_m, map_output.cloud_max_depth_m);  // checked before the run
    // The sessions: --session, each; or --tum / --rawlog, one.
    std::vector<gasp::DepthSequenceOptions> sessions;
    for (const std::string& spec : session_specs) sessions.push_back(gasp::tools::sessionOptions(spec, input));
    if (sessions.empty()) sessions.push_back(input);
    const std::size_t n_sessions = sessions.size();
    std::vector<std::string> trajectory_paths, odometry_paths;
    std::vector<std::pair<std::string, std::string>> output_paths;
    for (std::size_t s = 0; s < n_sessions; ++s) {
      trajectory_paths.push_back(gasp::tools::sessionPath(out_path, s, n_sessions));
      odometry_paths.push_back(gasp::tools::sessionPath(odometry_out, s, n_sessions));
      output_paths.push_back({"--out", trajectory_paths.back()});
      output_paths.push_back({"--odometry-out", odometry_paths.back()});
    }
    for (const auto& p : std::vector<std::pair<std::string, std::string>>{
             {"--graph", graph_path}, {"--frames-csv", frames_csv}, {"--loops-csv", loops_csv},
             {"--marginals-csv", marginals_csv}, {"--sessions-report", sessions_report}})
      output_paths.push_back(p);
    for (const auto& p : gasp::tools::mapOutputPaths(map_output)) output_paths.push_back(p);
    std::vector<std::vector<std::string>> session_inputs;  // each session's files, listed once
    std::vector<std::string> input_files;
    for (const auto& session : sessions) {
      session_inputs.push_back(gasp::tools::sequenceInputs(session, ""));
      input_files.insert(input_files.end(), session_inputs.back().begin(), session_inputs.back().end());
    }
    if (!gt_path.empty()) input_files.push_back(gt_path);
    const gasp::tools::InputFiles inputs(input_files);
    gasp::tools::RunOutputs outputs(output_paths, inputs);  // before the run

    // Every input opened before the run: a missing one is reported now, not after the others.
    std::vector<gasp::DepthSequence> sequences;
    for (const auto& session : sessions) sequences.emplace_back(session);
    // A LiDAR's sweeps: the pair's values from the params' lidar section (docs/lidar.md); one
    // kind of input for all sessions. A session whose first frame cannot be read is reported by
    // its run below, as without the look ahead.
    std::optional<bool> first_kind;
    gasp::Isometry3 first_mounting = gasp::Isometry3::Identity();  // the first frame's, as the graph takes it
    for (std::size_t s = 0; s < sequences.size(); ++s) {
      const gasp::RgbdFrame* first = nullptr;
      try {
        first = sequences[s].peek();
      } catch (const gasp::Error&) {
        if (n_sessions == 1) throw;
        continue;
      }
      if (!first) continue;
      if (!first_kind) {
        first_kind = first->isSweep();
        first_mounting = first->T_robot_camera;
      }
      if (first->isSweep() != *first_kind)
        throw gasp::Error(sequences[s].describe() + ": " + (first->isSweep() ? "LiDAR sweeps" : "depth images") +
                          ", an earlier session's are " + (*first_kind ? "LiDAR sweeps" : "depth images") +
                          " (one kind of sensor per map)");
    }
    const bool sweeps = first_kind.value_or(false);
    if (sweeps && !map_output.cloud_path.empty())
      std::fprintf(stderr, "note: --cloud leaves out the sweeps' returns beyond %g m (--cloud-max-depth)\n",
                   map_output.cloud_max_depth_m);
    if (sweeps) params = gasp::lidarSlamParams(params);
    // The job's registrations journaled (--checkpoint): named by the effective parameters and the
    // sessions, so that a journal answers only the job that wrote it.
    std::optional<gasp::RegistrationLog> registrations;
    if (!checkpoint_path.empty()) {
      checkJournalPath(checkpoint_path, resume, inputs, output_paths);
      std::string job = gasp::paramsYaml(params);
      for (std::size_t s = 0; s < n_sessions; ++s) job += "\nsession " + sessionFingerprint(sessions[s], session_inputs[s]);
      registrations.emplace(resume ? gasp::RegistrationLog::read(checkpoint_path, job) : gasp::RegistrationLog(job));
      registrations->journalTo(checkpoint_path);
      if (resume) std::printf("checkpoint: %zu registrations from %s\n", registrations->size(), checkpoint_path.c_str());
      if (params.loop.background)
        std::fprintf(stderr, "note: --checkpoint with background loop searches: a resumed run answers what the journal "
                             "holds, but which candidates it searches follows how far tracking got (for the "
                             "uninterrupted run's graph: loop_closure.background: false)\n");
    }
    gasp::CandidateRegistrar registrar;  // empty: in this process
#ifdef GASP_WITH_MPI
    std::optional<gasp::mpi::RegistrarPool> pool;
    if (mpi) {
      gasp::ByteWriter context;  // what a rank tracking a session needs beyond the command line
      context.putFlag(sweeps);
      context.putPose(first_mounting);
      pool.emplace(*mpi, gasp::paramsYaml(params), sweeps, n_sessions, context.take());
      registrar = pool->registrar();
      if (mpi->size() > 1)
        std::printf("mpi: %d ranks: the sessions tracked on rank%s, the loop registrations on whichever rank is free\n",
                    mpi->size(), mpi->size() == 2 ? " 1" : ("s 1-" + std::to_string(mpi->size() - 1)).c_str());
      else
        std::printf("mpi: 1 rank (not started by mpirun -np N?), the loop registrations in this process\n");
    }
#endif
    if (registrations) registrar = registrations->registrar(registrar);
    std::optional<gasp::DepthSlam> slam;
    gasp::Isometry3 T_robot_camera = gasp::Isometry3::Identity();
    std::vector<gasp::RgbdFrame> keyframes;  // for --simplemap and --cloud
    const bool keep_keyframes = map_output.wanted();
    std::vector<gasp::tools::SessionRun> runs;
    const auto run_start = std::chrono::steady_clock::now();
    for (std::size_t s = 0; s < n_sessions; ++s) {
      gasp::DepthSequence& sequence = sequences[s];
      gasp::tools::SessionRun run;
      run.input = sequence.describe() + (session_specs.empty() ? "" : " (" + session_specs[s] + ")");
      run.first_frame = slam ? slam->odometry().frames().size() : 0;
      if (n_sessions > 1) std::printf("session %zu: %s\n", s + 1, run.input.c_str());
      gasp::tools::reportIntrinsics(stdout, sequence.intrinsicsSummary(), sequence.intrinsicsWarning());
      run.ground_truth = gt_path.empty() ? sequence.groundTruth() : gasp::readTumTrajectory(gt_path);
      bool session_started = false;
      // Before a frame goes into the graph: the graph made at the first frame (world = the first
      // frame's robot frame: the first camera sits at its sensorPose), a session started at its
      // first, in the world of its own first robot frame, as the first session did.
      const auto beforeFrame = [&](const gasp::Isometry3& T_robot_frame_camera) {
        if (!slam) {
          T_robot_camera = T_robot_frame_camera;
          slam.emplace(params, T_robot_camera);
          if (registrar) slam->setRegistrar(registrar);
        } else if (!session_started) {
          if (!T_robot_frame_camera.isApprox(T_robot_camera, 1e-9)) throw gasp::Error(kOtherMounting);
          slam->startSession(T_robot_camera);
        }
        session_started = true;
      };
      const auto afterFrame = [&](const gasp::OdometryFrame& f) {
        if (slam->odometry().frames().size() % 50 == 0)
          std::fprintf(stderr, "frame %zu: %zu tracked of %zu, %zu loop closures\n", f.index,
                       slam->odometry().trackedCount(), slam->odometry().frames().size(), slam->loopClosures().size());
      };
      // With several sessions, one that fails ends there (partial) and the others still run.
      try {
#ifdef GASP_WITH_MPI
        if (pool && pool->tracksElsewhere()) {
          // Tracked on another rank: its frames replayed into the graph as they come.
          std::string message;
          bool ended = false;
          try {
            while (!(ended = pool->nextTracked(s, message))) {
              gasp::tools::HandedFrame h;
              try {
                h = gasp::tools::handedFrameFromBytes(message, params);
              } catch (const gasp::Error& e) {
                throw gasp::JobError(e.what());
              }
              beforeFrame(first_mounting);  // the other rank checked the session's mounting
              const gasp::OdometryFrame& f = slam->addTracked(std::move(h.tracked));
              if (f.keyframe && keep_keyframes) {
                if (!h.keyframe) throw gasp::JobError("MPI: a keyframe came without its frame for the map");
                keyframes.push_back(std::move(*h.keyframe));
              }
              afterFrame(f);
            }
          } catch (const gasp::Error&) {
            if (n_sessions > 1)  // the session's frames not taken: the next session's come after them
              while (!ended) ended = pool->nextTracked(s, message);
            throw;
          }
          gasp::tools::HandedEnd end;
          try {
            end = gasp::tools::handedEndFromBytes(message);
          } catch (const gasp::Error& e) {
            throw gasp::JobError(e.what());
          }
          // A first frame that passed the mounting check and then threw: one process had started
          // the session (made the graph) before it threw.
          if (end.reached && !session_started) beforeFrame(first_mounting);
          if (end.threw) throw gasp::Error(end.end.error);
          run.end = end.end;
        } else
#endif
        {
          // Each frame is segmented while the one before it is registered (frames_ahead.h).
          run.end = gasp::tools::forEachFrameWithViewAhead(sequence, params.odometry, sequential, [&](const gasp::RgbdFrame& frame, auto segmented) {
            beforeFrame(frame.T_robot_camera);
            const gasp::OdometryFrame& f = addTo(*slam, frame, std::move(segmented));
            if (f.keyframe && keep_keyframes) keyframes.push_back(mapKeyframe(frame, f, slam->odometry().keyframeView()));
            afterFrame(f);
          });
        }
      } catch (const gasp::Error& e) {
        if (n_sessions == 1) throw;
        run.end.complete = false;
        run.end.error = sequence.describe() + ": " + e.what();
      }
      if (n_sessions == 1 && !slam) throw gasp::Error(sequence.describe() + ": no frame to use");
      const std::size_t frame_count = slam ? slam->odometry().frames().size() : 0;
      run.frames = frame_count - run.first_frame;
      run.end.frames = run.frames;
      for (std::size_t i = run.first_frame; i < frame_count; ++i) run.tracked += slam->odometry().frames()[i].tracked ? 1 : 0;
      runs.push_back(std::move(run));
    }
    if (!slam) throw gasp::Error("no session gave a frame to use");
    slam->finishLoops();  // the searches still running: part of the wall time
    const double wall_s = gasp::msSince(run_start) / 1000.0;

    const auto& frames = slam->odometry().frames();
    const gasp::Trajectory trajectory = slam->trajectory(), odometry_trajectory = slam->odometry().trajectory();
    for (std::size_t s = 0; s < n_sessions; ++s) {
      gasp::OutputFile& out = outputs.at("--out", trajectory_paths[s]);
      gasp::writeTumTrajectory(out.stream(), gasp::tools::sessionTrajectory(trajectory, runs[s]),
                               gasp::tools::trajectoryHeader(sweeps ? "LiDAR trajectory by gasp-slam (optimised)"
                                                                      : "depth camera trajectory by gasp-slam (optimised)",
                                                               runs[s].end));
      out.commit();
      if (odometry_out.empty()) continue;
      gasp::OutputFile& f = outputs.at("--odometry-out", odometry_paths[s]);
      gasp::writeTumTrajectory(f.stream(), gasp::tools::sessionTrajectory(odometry_trajectory, runs[s]),
                               gasp::tools::trajectoryHeader(sweeps ? "LiDAR trajectory by gasp-slam (odometry)"
                                                                      : "depth camera trajectory by gasp-slam (odometry)",
                                                               runs[s].end));
      f.commit();
    }
    if (auto* f = outputs.find("--frames-csv")) {
      gasp::tools::writeFramesCsv(f->stream(), frames);
      f->commit();
    }
    if (auto* f = outputs.find("--loops-csv")) {
      writeLoopsCsv(f->stream(), slam->attempts());
      f->commit();
    }
    if (auto* graph_file = outputs.find("--graph")) {
      const auto g = gasp::toPoseGraph(slam->poses(), slam->constraints(), T_robot_camera);
      gasp::tools::writeGraph(*graph_file, g.graph);
      std::printf("graph: %s (%zu nodes, %zu edges%s)\n", graph_path.c_str(), g.graph.nodes.size(), g.graph.edgeCount(),
                  g.skipped_constraints ? (", " + std::to_string(g.skipped_constraints) + " without a covariance left out").c_str() : "");
    }
    // The poses' uncertainty in the graph: relative to the first frame of each piece.
    gasp::PoseGraphMarginals marginals;
    try {
      marginals = slam->marginals();
    } catch (const gasp::Error& e) {  // no covariance, but the outputs are still written
      marginals.message = e.what();
    }
    if (auto* f = outputs.find("--marginals-csv")) {
      gasp::tools::writeMarginalsCsv(f->stream(), marginals, trajectory);
      f->commit();
    }
    std::vector<gasp::Isometry3> keyframe_poses;
    std::vector<gasp::Matrix6> keyframe_covariances;  // a keyframe no constraint reaches is its own piece: zero
    for (const auto& f : frames)
      if (f.keyframe && keep_keyframes) {
        keyframe_poses.push_back(slam->poses()[f.index]);
        keyframe_covariances.push_back(marginals.covariance[f.index].value_or(gasp::Matrix6::Zero()));
      }
    if (!marginals.computed) {
      keyframe_covariances.clear();
      if (!map_output.simplemap_path.empty())
        std::fprintf(stderr, "warning: the simple map's poses carry a zero covariance: %s\n", marginals.message.c_str());
    } else if (n_sessions > 1 && map_output.wanted() && slam->pieceCount() > 1) {
      std::fprintf(stderr, "warning: the graph is in %zu pieces: sessions no constraint joins stay in the worlds they "
                           "started in, and the simple map and the cloud hold them on top of each other (the sessions "
                           "report says which are joined)\n",
                   slam->pieceCount());
    } else if (!map_output.simplemap_path.empty() && slam->pieceCount() > 1) {
      std::fprintf(stderr, "warning: the graph is in %zu pieces: a simple-map pose's covariance is relative to the first "
                           "keyframe of its piece, and the pieces are placed only by the odometry's prediction\n",
                   slam->pieceCount());
    }
    gasp::tools::writeMapOutputs(map_output, outputs, keyframes, keyframe_poses, "keyframes", keyframe_covariances);

    gasp::tools::printOdometrySummary(slam->odometry());
    gasp::tools::printThroughput(frames, wall_s);
    std::size_t tried = 0, relocalisations = 0, failed = 0;
    for (const auto& a : slam->attempts()) {  // an attempt is accepted while its closure is in the graph
      tried += a.relocalisation ? 0 : 1;
      relocalisations += a.accepted && a.relocalisation ? 1 : 0;
      failed += a.reason.rfind(gasp::kRegistrationFailed, 0) == 0 ? 1 : 0;
    }
    std::printf("loop_closures: %zu (%zu registrations tried; %zu relocalisations)\n",
                slam->loopClosures().size() - relocalisations, tried, relocalisations);
    // A registration that threw is not the job's end (loop_search.h), but it is not silent either.
    if (failed > 0)
      std::fprintf(stderr, "warning: %zu loop registrations failed with an error (their reasons: --loops-csv)\n", failed);
    std::printf("optimisations: %zu (%.1f ms in all)\n", slam->optimisationCount(), slam->optimisationMs());
    if (registrations)
      std::printf("checkpoint: %s (%zu registrations made, %zu answered from it)\n", checkpoint_path.c_str(),
                  registrations->registered(), registrations->answered());
#ifdef GASP_WITH_MPI
    if (pool)
      std::printf("mpi: %zu pairs registered on the other ranks and %zu on rank 0 while none was free, %zu views sent "
                  "(%.1f MB); rank 0 waited %.1f s for tracked frames\n",
                  pool->pairsSent(), pool->pairsHere(), pool->viewsSent(), pool->megabytesSent(), pool->trackedWaitS());
#endif
    std::printf("graph_pieces: %zu (odometry alone: %zu)\n", slam->pieceCount(), slam->odometry().componentCount());
    const std::size_t tracked = slam->odometry().trackedCount();
    if (n_sessions == 1) {
      const gasp::Trajectory& gt = runs[0].ground_truth;
      std::printf("trajectory: %s\n", out_path.c_str());
      gasp::tools::printEvaluation(gt, odometry_trajectory, tracked, "odometry_");
      gasp::tools::printEvaluation(gt, trajectory, tracked);
      gasp::tools::printMarginals(marginals, trajectory, gt);
    } else {
      gasp::tools::printMarginals(marginals, trajectory, {});
    }
    if (auto* f = outputs.find("--sessions-report")) {
      gasp::tools::reportSessions(runs, *slam, trajectory, trajectory_paths, &f->stream());
      f->commit();
    } else if (n_sessions > 1) {
      gasp::tools::reportSessions(runs, *slam, trajectory, trajectory_paths, nullptr);
    }
    int partial = -1;
    for (const auto& run : runs)
      if (const int code = gasp::tools::reportPartial(run.end); code >= 0) partial = code;
    if (partial >= 0) return partial;
    const std::size_t lost = frames.size() - tracked;
    if (lost > 0) std::printf("not_tracked: %zu frames (poses predicted; reasons in --frames-csv)\n", lost);
    if (lost > 0 || slam->pieceCount() > 1) return 3;
  } catch (const std::exception& e) {  // gasp::Error, and MRPT's when an output cannot be written
    std::cerr << "error: " << gasp::exceptionMessage(e) << '\n';
    return 1;
  }
  return 0;
}
