// Intrinsics, views (a depth image segmented into surface patches), the registration of two views,
// and TUM folders, bound for Python. The pipeline decides; this file converts and checks.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <utility>

#include "arrays.h"
#include "bindings.h"
#include "gasp/core/error.h"
#include "gasp/core/tum_dataset.h"
#include "gasp/pipeline/depth_view.h"
#include "gasp/pipeline/pair_registration.h"

namespace gasp::python {

namespace {

/// A segmented view, shared with the registrations made from it.
struct View {
  std::shared_ptr<const DepthView> view;

  const SuperpixelSegmentation& seg() const { return view->segmentation; }
  std::size_t size() const { return seg().patches.size(); }

  template <class Get>
  py::array_t<double> rows3(Get get) const {
    py::array_t<double> out({static_cast<py::ssize_t>(size()), py::ssize_t{3}});
    auto o = out.mutable_unchecked<2>();
    for (std::size_t i = 0; i < size(); ++i) {
      const Eigen::Vector3d v = get(seg().patches[i]);
      for (int k = 0; k < 3; ++k) o(static_cast<py::ssize_t>(i), k) = v[k];
    }
    return out;
  }
  template <class T, class Get>
  py::array_t<T> column(Get get) const {
    py::array_t<T> out(static_cast<py::ssize_t>(size()));
    auto o = out.template mutable_unchecked<1>();
    for (std::size_t i = 0; i < size(); ++i) o(static_cast<py::ssize_t>(i)) = static_cast<T>(get(seg().patches[i]));
    return out;
  }
};

/// A registration and the views its patch indices refer to (the finer-scale retry's own when it ran).
struct Registration {
  PairResult r;
  View source, target;
};

py::array_t<std::int32_t> pairsArray(const std::vector<PatchAssociation>& pairs) {
  py::array_t<std::int32_t> out({static_cast<py::ssize_t>(pairs.size()), py::ssize_t{2}});
  auto o = out.mutable_unchecked<2>();
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    o(static_cast<py::ssize_t>(i), 0) = pairs[i].a;
    o(static_cast<py::ssize_t>(i), 1) = pairs[i].b;
  }
  return out;
}

View makeView(const py::handle& depth, const CameraIntrinsics& intrinsics, const SuperpixelParams& params,
              double units_per_metre, const std::string& what) {
  const cv::Mat depth_m = depthFromArray(depth, intrinsics, units_per_metre, what);
  py::gil_scoped_release release;
  return View{std::make_shared<const DepthView>(makeDepthView(depth_m, intrinsics, params))};
}

/// One side of a pair: a View as given, or a depth image [m] still to segment.
struct PairSide {
  std::optional<View> view;
  cv::Mat depth_m;
};

PairSide pairSide(const py::object& x, const std::optional<CameraIntrinsics>& intrinsics, double units_per_metre,
                  const std::string& what) {
  if (py::isinstance<View>(x)) return {x.cast<View>(), {}};
  if (!intrinsics)
    throw py::value_error(what + ": a depth array needs intrinsics (gasp.Intrinsics); a gasp.View does not");
  return {std::nullopt, depthFromArray(x, *intrinsics, units_per_metre, what + " depth")};
}

py::dict timingsDict(const PairTimings& t) {
  py::dict d;
  d["association_ms"] = t.association_ms, d["ransac_ms"] = t.ransac_ms, d["refine_ms"] = t.refine_ms;
  d["dense_ms"] = t.dense_ms, d["guided_ms"] = t.guided_ms, d["certify_ms"] = t.certify_ms;
  d["retry_segmentation_ms"] = t.retry_segmentation_ms, d["returns_ms"] = t.returns_ms;
  d["ground_search_ms"] = t.ground_search_ms, d["sweep_motion_ms"] = t.sweep_motion_ms, d["total_ms"] = t.total();
  return d;
}

py::dict freeSpaceDict(const VisibilityCheck& v) {
  py::dict d;
  d["passed"] = v.passed, d["consistent"] = v.consistent, d["occluded"] = v.occluded, d["violations"] = v.violations;
  d["violation_ratio"] = v.violation_ratio, d["occluded_ratio"] = v.occluded_ratio, d["reason"] = v.reason;
  return d;
}

}  // namespace

void bindPairs(py::module_& m) {
  py::class_<CameraIntrinsics>(m, "Intrinsics",
                               "A pinhole depth camera: image size [px], focal lengths and principal point [px], "
                               "lens distortion k1 k2 p1 p2 k3 (resampled away before segmenting).")
      .def(py::init([](double fx, double fy, double cx, double cy, int width, int height,
                       const std::array<double, 5>& distortion) {
             CameraIntrinsics k;
             k.fx = fx, k.fy = fy, k.cx = cx, k.cy = cy, k.width = width, k.height = height, k.distortion = distortion;
             k.validate();
             return k;
           }),
           py::arg("fx"), py::arg("fy"), py::arg("cx"), py::arg("cy"), py::arg("width"), py::arg("height"),
           py::arg("distortion") = std::array<double, 5>{})
      .def_static("preset", &CameraIntrinsics::fromPreset, py::arg("name"),
                  "A preset by name: fr1, fr2, fr3 (TUM RGB-D's Freiburg cameras) or ros (525, 319.5, 239.5).")
      .def_static("load", [](const std::filesystem::path& path) { return CameraIntrinsics::load(path.string()); },
                  py::arg("path"), "Reads an intrinsics file (docs/formats.md).")
      .def("save", [](const CameraIntrinsics& k, const std::filesystem::path& path) { k.save(path.string()); },
           py::arg("path"))
      .def_readonly("fx", &CameraIntrinsics::fx)
      .def_readonly("fy", &CameraIntrinsics::fy)
      .def_readonly("cx", &CameraIntrinsics::cx)
      .def_readonly("cy", &CameraIntrinsics::cy)
      .def_readonly("width", &CameraIntrinsics::width)
      .def_readonly("height", &CameraIntrinsics::height)
      .def_readonly("distortion", &CameraIntrinsics::distortion)
      .def_property_readonly("K", [](const CameraIntrinsics& k) {
        Eigen::Matrix3d K;
        K << k.fx, 0, k.cx, 0, k.fy, k.cy, 0, 0, 1;
        return matrixArray(K);
      }, "The 3x3 camera matrix.")
      .def("__eq__", [](const CameraIntrinsics& a, const CameraIntrinsics& b) { return a == b; }, py::is_operator())
      .def("__ne__", [](const CameraIntrinsics& a, const CameraIntrinsics& b) { return a != b; }, py::is_operator())
      .def("__repr__", [](const CameraIntrinsics& k) {
        char text[256];
        std::snprintf(text, sizeof text, "gasp.Intrinsics(fx=%.17g, fy=%.17g, cx=%.17g, cy=%.17g, width=%d, height=%d)",
                      k.fx, k.fy, k.cx, k.cy, k.width, k.height);
        return std::string(text);
      });

  py::class_<View>(m, "View",
                   "A depth image segmented into regularised surface patches (the pipeline's first stage). "
                   "Arrays are copies, made when read.")
      .def("__len__", &View::size)
      .def_property_readonly("labels", [](const View& v) { return imageArray<std::int32_t>(v.seg().labels); },
                             "(height, width) int32: the patch of each pixel, -1 where none (no depth, or dropped)")
      .def_property_readonly("centroids", [](const View& v) { return v.rows3([](const SurfacePatch& p) { return p.centroid; }); },
                             "(N, 3) float64: each patch's centroid in the camera frame [m] (x right, y down, z ahead)")
      .def_property_readonly("normals", [](const View& v) { return v.rows3([](const SurfacePatch& p) { return p.normal; }); },
                             "(N, 3) float64: each patch's unit normal, towards the camera")
      .def_property_readonly("areas", [](const View& v) { return v.column<double>([](const SurfacePatch& p) { return p.area_m2; }); },
                             "(N,) float64: each patch's surface area [m^2]")
      .def_property_readonly("pixel_counts", [](const View& v) { return v.column<std::int32_t>([](const SurfacePatch& p) { return p.pixel_count; }); },
                             "(N,) int32: pixels in each patch")
      .def_property_readonly("planarity", [](const View& v) { return v.column<double>([](const SurfacePatch& p) { return p.planarity; }); },
                             "(N,) float64: 1 - lambda_min / lambda_mid of each patch's point covariance (1: flat)")
      .def_property_readonly("adjacency", [](const View& v) { return v.seg().adjacency; },
                             "list of lists: the patches adjacent to each patch")
      .def_property_readonly("depth", [](const View& v) { return imageArray<float>(v.view->depth_m); }, "(height, width) float32: the depth segmented [m] (undistorted)")
      .def_property_readonly("coverage", [](const View& v) { return v.seg().stats.coverage(); },
                             "share of the valid pixels inside a patch")
      .def_property_readonly("segmentation_ms", [](const View& v) { return v.seg().timings.total(); })
      .def("__repr__", [](const View& v) { return "<gasp.View: " + std::to_string(v.size()) + " patches>"; });

  py::class_<Registration>(m, "Registration",
                           "The registration of a source view to a target view: T_target_source maps the source "
                           "camera's frame into the target's. success: a full pose is claimed; partial: a pose free "
                           "along unobservable_directions; neither: no estimate, reason says why.")
      .def_property_readonly("success", [](const Registration& g) { return g.r.pose.success; })
      .def_property_readonly("partial", [](const Registration& g) { return g.r.pose.partial; })
      .def_property_readonly("estimated", [](const Registration& g) { return g.r.pose.estimated(); },
                             "success or partial")
      .def_property_readonly("reason", [](const Registration& g) { return g.r.pose.reason; })
      .def_property_readonly("T_target_source", [](const Registration& g) { return poseArray(g.r.pose.T_target_source); },
                             "(4, 4) float64; the estimate also when none is claimed (then meaningless)")
      .def_property_readonly("information", [](const Registration& g) { return matrixArray(g.r.pose.information); },
                             "(6, 6): of the left perturbation [translation m; rotation rad] of T_target_source, "
                             "in the target frame (the refinement's)")
      .def_property_readonly("edge_information", [](const Registration& g) { return matrixArray(g.r.edge_information); },
                             "(6, 6): information with the model error added, as a pose graph takes it; zero without a pose")
      .def_property_readonly("degenerate", [](const Registration& g) { return g.r.pose.degenerate; })
      .def_property_readonly("unobservable_directions",
                             [](const Registration& g) { return matrixArray(g.r.pose.unobservable_directions); },
                             "(6, k): the directions the pose leaves free, as left perturbations [t; r]")
      .def_property_readonly("views_free_directions", [](const Registration& g) { return g.r.views_free_directions; },
                             "directions the views' own patch geometry leaves free (0: each view fixes a pose)")
      .def_property_readonly("uniqueness_log_ratio", [](const Registration& g) { return g.r.uniqueness_log_ratio; },
                             "log L(claimed) - log L(best distinct alternative); NaN when there was none")
      .def_property_readonly("free_space", [](const Registration& g) { return freeSpaceDict(g.r.visibility); },
                             "the free-space test of the final pose: passed, counts, ratios, reason")
      .def_property_readonly("inliers", [](const Registration& g) { return g.r.pose.num_inliers; })
      .def_property_readonly("rms_residual_m", [](const Registration& g) { return g.r.pose.rms_residual_m; })
      .def_property_readonly("verified", [](const Registration& g) { return pairsArray(g.r.verified); },
                             "(K, 2) int32: [source patch, target patch] associations verified at the final pose")
      .def_property_readonly("associations", [](const Registration& g) { return pairsArray(g.r.association.associations); },
                             "(K, 2) int32: [source patch, target patch] associations made without a pose (free)")
      .def_property_readonly("retried", [](const Registration& g) { return g.r.retried; },
                             "the finer-scale retry ran (the default scale gave no estimate)")
      .def_property_readonly("source", [](const Registration& g) { return g.source; },
                             "the source view the patch indices refer to")
      .def_property_readonly("target", [](const Registration& g) { return g.target; })
      .def_property_readonly("timings", [](const Registration& g) { return timingsDict(g.r.timings); },
                             "wall time per stage [ms], segmentation excluded")
      .def("__repr__", [](const Registration& g) {
        return std::string("<gasp.Registration: ") +
               (g.r.pose.success ? "success" : g.r.pose.partial ? "partial" : "no estimate (" + g.r.pose.reason + ")") +
               ", " + std::to_string(g.r.verified.size()) + " verified associations>";
      });

  m.def("_segment",
        [](const py::handle& depth, const CameraIntrinsics& intrinsics, const std::string& params_yaml,
           double units_per_metre) {
          const SlamParams params = paramsFromYaml(params_yaml);
          return makeView(depth, intrinsics, params.odometry.pair.segment, units_per_metre, "depth");
        },
        py::arg("depth"), py::arg("intrinsics"), py::arg("params_yaml"), py::arg("depth_units_per_metre"));

  m.def("_register",
        [](const py::object& source, const py::object& target, const std::optional<CameraIntrinsics>& intrinsics,
           const std::string& params_yaml, double units_per_metre) {
          const SlamParams params = paramsFromYaml(params_yaml);
          const PairParams& pair = params.odometry.pair;
          PairSide s = pairSide(source, intrinsics, units_per_metre, "source");
          PairSide t = pairSide(target, intrinsics, units_per_metre, "target");
          Registration g;
          {
            py::gil_scoped_release release;
            const auto shared = [](DepthView v) { return View{std::make_shared<const DepthView>(std::move(v))}; };
            if (!s.view && !t.view) {  // both segmented at once, as registerDepthImages() does
              auto views = makeDepthViews(s.depth_m, t.depth_m, *intrinsics, pair.segment);
              s.view = shared(std::move(views.first)), t.view = shared(std::move(views.second));
            }
            if (!s.view) s.view = shared(makeDepthView(s.depth_m, *intrinsics, pair.segment));
            if (!t.view) t.view = shared(makeDepthView(t.depth_m, *intrinsics, pair.segment));
            g.source = *s.view, g.target = *t.view;
            g.r = registerViews(*g.source.view, *g.target.view, pair);
          }
          if (g.r.retry_views) {  // the indices refer to the retry's views, which the result keeps
            g.source.view = std::shared_ptr<const DepthView>(g.r.retry_views, &g.r.retry_views->first);
            g.target.view = std::shared_ptr<const DepthView>(g.r.retry_views, &g.r.retry_views->second);
          }
          return g;
        },
        py::arg("source"), py::arg("target"), py::arg("intrinsics"), py::arg("params_yaml"),
        py::arg("depth_units_per_metre"));

  py::class_<TumDataset>(m, "TumFolder",
                         "A TUM RGB-D folder (depth.txt, and groundtruth.txt when present). Depth is resampled to "
                         "the pinhole camera when the intrinsics carry lens distortion; `intrinsics` is that camera.")
      .def(py::init([](const std::filesystem::path& path, const std::optional<CameraIntrinsics>& intrinsics) {
             TumDataset::Options o;
             o.intrinsics = intrinsics;
             py::gil_scoped_release release;
             return TumDataset::open(path.string(), o);
           }),
           py::arg("path"), py::arg("intrinsics") = std::nullopt)
      .def("__len__", &TumDataset::size)
      .def_property_readonly("intrinsics", &TumDataset::intrinsics)
      .def_property_readonly("timestamps", [](const TumDataset& d) {
        py::array_t<double> out(static_cast<py::ssize_t>(d.size()));
        for (std::size_t i = 0; i < d.size(); ++i) out.mutable_at(static_cast<py::ssize_t>(i)) = d.frame(i).timestamp;
        return out;
      })
      .def("depth", [](const TumDataset& d, std::size_t i) {
        cv::Mat depth;
        {
          py::gil_scoped_release release;  // the PNG decoded and resampled
          depth = d.loadDepth(i);
        }
        return imageArray<float>(depth);
      }, py::arg("index"), "(height, width) float32: frame `index`'s depth [m], 0 where none")
      .def("ground_truth", [](const TumDataset& d, std::size_t i, double offset_s) -> std::optional<py::array_t<double>> {
        const auto T = d.groundTruthOf(i, offset_s);
        if (!T) return std::nullopt;
        return poseArray(*T);
      }, py::arg("index"), py::arg("offset_s") = 0.0,
           "T_world_camera of frame `index` (4x4), looked up offset_s later; None without ground truth near it");
}

}  // namespace gasp::python
