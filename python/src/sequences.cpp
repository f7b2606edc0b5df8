// Trajectories, odometry and SLAM over a TUM folder or a rawlog, and the ATE, bound for Python.
// The frame loop is the programs' (gasp-odometry, gasp-slam with one session): frames added in
// order, a LiDAR's sweeps with the params' lidar section.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <Python.h>

#include <filesystem>
#include <optional>

#include "arrays.h"
#include "bindings.h"
#include "gasp/core/error.h"
#include "gasp/core/tum_trajectory.h"
#include "gasp/eval/ate.h"
#include "gasp/odometry/odometry.h"
#include "gasp/rawlog/depth_sequence.h"
#include "gasp/slam/depth_slam.h"

PYBIND11_MAKE_OPAQUE(gasp::Trajectory)  // a class of its own (arrays on demand), not a list

namespace gasp::python {

namespace {

py::array_t<double> timestampsArray(const Trajectory& t) {
  py::array_t<double> out(static_cast<py::ssize_t>(t.size()));
  for (std::size_t i = 0; i < t.size(); ++i) out.mutable_at(static_cast<py::ssize_t>(i)) = t[i].timestamp;
  return out;
}

py::array_t<double> posesArray(const Trajectory& t) {
  py::array_t<double> out({static_cast<py::ssize_t>(t.size()), py::ssize_t{4}, py::ssize_t{4}});
  auto o = out.mutable_unchecked<3>();
  for (std::size_t i = 0; i < t.size(); ++i)
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c) o(static_cast<py::ssize_t>(i), r, c) = t[i].T_world_camera.matrix()(r, c);
  return out;
}

/// A trajectory from Python's arrays: timestamps (N,) ascending and finite, poses (N, 4, 4) rigid.
Trajectory trajectoryFromArrays(const py::handle& timestamps, const py::handle& poses) {
  const auto t = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(timestamps);
  if (!t || t.ndim() != 1) throw py::value_error("timestamps: expected a 1-D array of seconds");
  if (!py::isinstance<py::array>(poses)) throw py::type_error("poses: expected a numpy array of shape (N, 4, 4)");
  const auto p = py::reinterpret_borrow<py::array>(poses);
  if (p.ndim() != 3 || p.shape(0) != t.shape(0) || p.shape(1) != 4 || p.shape(2) != 4)
    throw py::value_error("poses: expected shape (" + std::to_string(t.shape(0)) + ", 4, 4), got " + shapeText(p));
  Trajectory out(static_cast<std::size_t>(t.shape(0)));
  for (py::ssize_t i = 0; i < t.shape(0); ++i) {
    const double ts = t.at(i);
    if (!std::isfinite(ts)) throw py::value_error("timestamps: value " + std::to_string(i) + " is not finite");
    if (i > 0 && !(ts > t.at(i - 1)))
      throw py::value_error("timestamps: not strictly increasing at index " + std::to_string(i));
    out[static_cast<std::size_t>(i)].timestamp = ts;
    out[static_cast<std::size_t>(i)].T_world_camera = poseFromArray(p[py::int_(i)], "poses[" + std::to_string(i) + "]");
  }
  return out;
}

/// What a run over a sequence gives.
struct SequenceRun {
  Trajectory trajectory;
  std::vector<OdometryFrame> frames;
  std::vector<PoseConstraint> loop_closures;
  Trajectory ground_truth;
  bool sweeps = false;
  std::string error;  ///< the input ended with this error after some frames (the run is partial)
};

/// The odometry of a tracker: itself, or a DepthSlam's.
const DepthOdometry& odometryOf(const DepthOdometry& odometry) { return odometry; }
const DepthOdometry& odometryOf(const DepthSlam& slam) { return slam.odometry(); }

/// Adds the sequence's frames in order to `tracker` (DepthOdometry or DepthSlam), the GIL released
/// while a frame is read and tracked; Ctrl-C between frames raises KeyboardInterrupt. An input
/// that breaks after some frames (a frame that cannot be read, or one the odometry refuses, which
/// it then does not add) ends the run there: partial, with the error.
template <class Tracker>
void addFrames(DepthSequence& sequence, Tracker& tracker, SequenceRun& run) {
  py::gil_scoped_release release;
  for (;;) {
    {
      py::gil_scoped_acquire acquire;
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
    }
    try {
      std::optional<RgbdFrame> frame = sequence.next();
      if (!frame) return;
      if (frame->isSweep()) tracker.addFrame(frame->timestamp, *frame->sweep);
      else tracker.addFrame(frame->timestamp, frame->depth_m, frame->depth_intrinsics);
    } catch (const Error& e) {
      if (odometryOf(tracker).frames().empty()) throw;
      run.error = exceptionMessage(e);  // keep what was tracked: the result says it is partial
      return;
    }
  }
}

DepthSequence openSequence(const std::filesystem::path& path, std::size_t first, std::size_t every,
                           std::size_t max_frames, const std::string& sensor, const std::string& intrinsics,
                           double units_per_metre) {
  DepthSequenceOptions in;
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) in.tum_dir = path.string();
  else in.rawlog_path = path.string();
  in.sweeps = true;  // a rawlog's LiDAR sweeps are frames too, as in the programs
  in.first = first, in.every = every, in.max_frames = max_frames, in.sensor_label = sensor;
  in.intrinsics = intrinsics, in.depth_units_per_metre = units_per_metre;
  return DepthSequence(in);
}

SequenceRun runSequence(const std::filesystem::path& path, bool slam, const std::string& params_yaml,
                        std::size_t first, std::size_t every, std::size_t max_frames, const std::string& sensor,
                        const std::string& intrinsics, double units_per_metre,
                        const std::optional<std::filesystem::path>& gt_path) {
  SlamParams params = paramsFromYaml(params_yaml);
  if (every == 0) throw py::value_error("every must be at least 1");
  SequenceRun run;
  std::optional<DepthSequence> sequence;
  Isometry3 T_robot_camera = Isometry3::Identity();
  {
    py::gil_scoped_release release;  // opening reads the input up to its first frame
    sequence.emplace(openSequence(path, first, every, max_frames, sensor, intrinsics, units_per_metre));
    const RgbdFrame* head = sequence->peek();
    if (!head) throw Error(path.string() + ": no depth frame in the input");
    run.sweeps = head->isSweep();
    T_robot_camera = head->T_robot_camera;
    run.ground_truth = gt_path ? readTumTrajectory(gt_path->string()) : sequence->groundTruth();
  }
  if (slam) {
    if (run.sweeps) params = lidarSlamParams(params);
    // As gasp-slam: world = the first frame's robot frame (the first camera at its sensorPose).
    DepthSlam tracker(params, T_robot_camera);
    addFrames(*sequence, tracker, run);
    py::gil_scoped_release release;
    tracker.finishLoops();
    run.trajectory = tracker.trajectory();
    run.frames = tracker.odometry().frames();
    run.loop_closures = tracker.loopClosures();
  } else {
    // As gasp-odometry: the first frame at the origin.
    DepthOdometry tracker(run.sweeps ? lidarOdometryParams(params.lidar, params.odometry) : params.odometry);
    addFrames(*sequence, tracker, run);
    run.trajectory = tracker.trajectory();
    run.frames = tracker.frames();
  }
  return run;
}

template <class Get>
py::array_t<bool> frameFlags(const SequenceRun& r, Get get) {
  py::array_t<bool> out(static_cast<py::ssize_t>(r.frames.size()));
  for (std::size_t i = 0; i < r.frames.size(); ++i) out.mutable_at(static_cast<py::ssize_t>(i)) = get(r.frames[i]);
  return out;
}

py::dict ateDict(const Trajectory& gt, const Trajectory& est, double max_dt, double offset_s) {
  eval::AteOptions o;
  o.max_dt = max_dt, o.offset = offset_s;
  const eval::AteResult a = eval::computeAte(gt, est, o);
  py::dict d;
  d["rmse_m"] = a.translation.rmse, d["mean_m"] = a.translation.mean, d["median_m"] = a.translation.median;
  d["max_m"] = a.translation.max, d["matched"] = a.translation.count;
  d["T_gt_estimate"] = poseArray(a.T_gt_est);
  return d;
}

}  // namespace

void bindSequences(py::module_& m) {
  py::class_<Trajectory>(m, "Trajectory", "Timestamped poses T_world_camera, sorted by time.")
      .def(py::init(&trajectoryFromArrays), py::arg("timestamps"), py::arg("poses"),
           "From timestamps (N,) [s], strictly increasing, and poses (N, 4, 4).")
      .def_static("read", [](const std::filesystem::path& path) { return readTumTrajectory(path.string()); },
                  py::arg("path"), "Reads a TUM trajectory file.")
      .def("save", [](const Trajectory& t, const std::filesystem::path& path) { writeTumTrajectory(path.string(), t); },
           py::arg("path"),
           "Writes the TUM format (timestamp tx ty tz qx qy qz qw): a temporary file in the same folder, then renamed.")
      .def("__len__", &Trajectory::size)
      .def_property_readonly("timestamps", &timestampsArray, "(N,) float64 [s]")
      .def_property_readonly("poses", &posesArray, "(N, 4, 4) float64: T_world_camera")
      .def("__repr__", [](const Trajectory& t) { return "<gasp.Trajectory: " + std::to_string(t.size()) + " poses>"; });

  py::class_<SequenceRun>(m, "SequenceRun",
                          "What odometry() or slam() gives: the trajectory (one pose per frame), each frame's "
                          "verdict and, for slam(), the loop closures.")
      .def_readonly("trajectory", &SequenceRun::trajectory)
      .def_property_readonly("ground_truth", [](const SequenceRun& r) -> std::optional<Trajectory> {
        if (r.ground_truth.empty()) return std::nullopt;
        return r.ground_truth;
      }, "the input's ground truth (a TUM folder's groundtruth.txt, or the file given), or None")
      .def_property_readonly("tracked", [](const SequenceRun& r) { return frameFlags(r, [](const OdometryFrame& f) { return f.tracked; }); },
                             "(N,) bool: the frame was registered (else its pose is predicted)")
      .def_property_readonly("keyframe", [](const SequenceRun& r) { return frameFlags(r, [](const OdometryFrame& f) { return f.keyframe; }); })
      .def_property_readonly("reasons", [](const SequenceRun& r) {
        std::vector<std::string> out;
        for (const auto& f : r.frames) out.push_back(f.reason);
        return out;
      }, "list of str: why each frame not tracked was not")
      .def_property_readonly("loop_closures", [](const SequenceRun& r) {
        py::array_t<std::int64_t> out({static_cast<py::ssize_t>(r.loop_closures.size()), py::ssize_t{2}});
        auto o = out.mutable_unchecked<2>();
        for (std::size_t i = 0; i < r.loop_closures.size(); ++i) {
          o(static_cast<py::ssize_t>(i), 0) = static_cast<std::int64_t>(r.loop_closures[i].from);
          o(static_cast<py::ssize_t>(i), 1) = static_cast<std::int64_t>(r.loop_closures[i].to);
        }
        return out;
      }, "(K, 2) int64: [from, to] frame indices of each accepted loop closure (slam() only)")
      .def_readonly("sweeps", &SequenceRun::sweeps, "the frames were a LiDAR's sweeps (poses are the LiDAR's)")
      .def_property_readonly("partial", [](const SequenceRun& r) { return !r.error.empty(); },
                             "the input ended with an error after some frames; `error` says which")
      .def_readonly("error", &SequenceRun::error)
      .def("ate", [](const SequenceRun& r, double max_dt, double offset_s) {
        if (r.ground_truth.empty()) throw py::value_error("ate: the input has no ground truth");
        return ateDict(r.ground_truth, r.trajectory, max_dt, offset_s);
      }, py::arg("max_dt") = 0.02, py::arg("offset_s") = 0.0, "ate() against the input's ground truth.")
      .def("__repr__", [](const SequenceRun& r) {
        std::size_t tracked = 0;
        for (const auto& f : r.frames) tracked += f.tracked;
        return "<gasp.SequenceRun: " + std::to_string(r.frames.size()) + " frames, " + std::to_string(tracked) +
               " tracked, " + std::to_string(r.loop_closures.size()) + " loop closures" + (r.error.empty() ? "" : ", partial") + ">";
      });

  m.def("_run_sequence", &runSequence, py::arg("path"), py::arg("slam"), py::arg("params_yaml"), py::arg("first"),
        py::arg("every"), py::arg("max_frames"), py::arg("sensor"), py::arg("intrinsics"),
        py::arg("depth_units_per_metre"), py::arg("ground_truth_path"));

  m.def("ate", &ateDict, py::arg("ground_truth"), py::arg("estimate"), py::arg("max_dt") = 0.02,
        py::arg("offset_s") = 0.0,
        "Absolute trajectory error as TUM's evaluate_ate.py: poses matched by time (|dt| < max_dt after adding "
        "offset_s to the estimate's), the estimate aligned rigidly; rmse_m, mean_m, median_m, max_m, matched, "
        "T_gt_estimate.");
}

}  // namespace gasp::python
