#include "gasp/pipeline/refine_stage.h"

#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>

#include "gasp/core/depth_image.h"
#include "gasp/core/error.h"
#include "slide_scan.h"

namespace gasp {

namespace {

/// Source edge points that T maps in front of the target camera onto a pixel with valid depth.
int edgePointsInView(const EdgePoints& source, const DepthView& target, const Isometry3& T_target_source) {
  int n = 0;
  const cv::Mat& d = target.depth_m;
  for (const Eigen::Vector3d& p : source.points) {
    double u = 0, v = 0;
    if (!target.projection.project(T_target_source * p, u, v)) continue;
    const int iu = static_cast<int>(std::lround(u)), iv = static_cast<int>(std::lround(v));
    if (iu < 0 || iv < 0 || iu >= d.cols || iv >= d.rows) continue;
    n += isValidDepth(d.at<float>(iv, iu)) ? 1 : 0;
  }
  return n;
}

/// One pair's dense problem: both views' edges found once (the target's in a KD-tree), the source
/// patch centroids whose RMS displacement is a round's step, and the solver.
class DenseProblem {
 public:
  DenseProblem(const DepthView& source, const DepthView& target, const RegistrationResult& hypothesis,
               const std::vector<PatchCorrespondence>& inliers, const RefineParams& params,
               const EdgeTargets* target_edges)
      : source_(source), target_(target), hypothesis_(hypothesis), inliers_(inliers), params_(params),
        edge_targets_(target_edges) {
    if (!params.edges.enabled) {
      edge_targets_ = nullptr;  // the caller's go unused
    } else if (edge_targets_) {
      source_edges_ = findEdgePoints(source, params.edges.terms);
    } else {
      tbb::parallel_invoke([&] { source_edges_ = findEdgePoints(source, params.edges.terms); },
                           [&] { own_edge_targets_ = std::make_unique<EdgeTargets>(target, params.edges.terms); });
      edge_targets_ = own_edge_targets_.get();
    }
    for (const auto& p : source.segmentation.patches)
      if (p.centroid.allFinite()) centroids_.push_back(p.centroid);
    evaluation_ = params.solver;
    evaluation_.max_iterations = 0;
  }

  double gateOfRound(int round) const {
    const auto& g = params_.dense.gates_m;
    return g[std::min<std::size_t>(static_cast<std::size_t>(round), g.size() - 1)];
  }

  /// The rounds from `start` (dense_rounds.h); edge gates are edge_gate_factor times the pixel gates.
  RegistrationResult refineFrom(const Isometry3& start, double edge_gate_factor, DenseRounds& rounds) const {
    DenseRoundsOps ops;
    ops.gather = [&](const Isometry3& T, int round) {
      GatedTerms gathered;
      ProjectiveTermParams pixels = params_.pixels;
      pixels.max_distance_m = gateOfRound(round);
      gathered.terms = projectiveTerms(source_, target_, T, pixels);
      gathered.pixel_terms = gathered.terms.size();
      gathered.pixel_gate_m = pixels.max_distance_m;
      gathered.edge_gate_m = edge_gate_factor * pixels.max_distance_m;
      if (edge_targets_) {
        const auto more = edge_targets_->terms(source_edges_, T, gathered.edge_gate_m);
        gathered.terms.insert(gathered.terms.end(), more.begin(), more.end());
      }
      return gathered;
    };
    ops.solve = [&](const Isometry3& from, const std::vector<PointToPlane>& terms, bool evaluate_only) {
      return refinePose(inliers_, from, evaluate_only ? evaluation_ : params_.solver, terms);
    };
    RegistrationResult first = hypothesis_;
    first.T_target_source = start;
    return runDenseRounds(first, centroids_, params_.dense, ops, rounds);
  }

  /// Whether the wide-edge refinement may help: target edges with a direction, weighted terms.
  bool edgesCanWiden() const {
    return edge_targets_ && edge_targets_->size() > 0 && params_.edges.terms.weight > 0.0 &&
           params_.edges.wide_gate_factor > 0.0 && !source_edges_.points.empty();
  }

  /// Of the source edge points that land on the target's depth at T, the share with a target edge
  /// within the last gate (-1: none lands). Points outside the target's view can have no partner,
  /// so a partial overlap alone does not lower it.
  double edgePairedShare(const Isometry3& T) const {
    const int in_view = edgePointsInView(source_edges_, target_, T);
    if (in_view == 0) return -1.0;
    const double last_gate = gateOfRound(params_.dense.rounds - 1);
    const double paired = 0.5 * static_cast<double>(edge_targets_->terms(source_edges_, T, last_gate).size()) /
                          static_cast<double>(in_view);
    return std::min(1.0, paired);
  }

 private:
  const DepthView& source_;
  const DepthView& target_;
  const RegistrationResult& hypothesis_;
  const std::vector<PatchCorrespondence>& inliers_;
  const RefineParams& params_;
  EdgePoints source_edges_;
  const EdgeTargets* edge_targets_;                // the caller's, or own_edge_targets_
  std::unique_ptr<EdgeTargets> own_edge_targets_;
  std::vector<Eigen::Vector3d> centroids_;
  RefinementParams evaluation_;
};

/// The wide-edge second refinement and the choice between the two: when the first failed, the
/// wide one is taken (the certificate still judges it); otherwise the pose that passes the
/// free-space test, and when both or neither pass, the one with the larger consistent share.
void widenEdges(const DenseProblem& problem, const Isometry3& start, const RefineParams& params,
                const FreeSpaceTest& free_space, Refinement& out) {
  if (!problem.edgesCanWiden()) return;
  if (out.pose.success) {
    const double share = problem.edgePairedShare(out.pose.T_target_source);
    if (share < 0.0) return;
    out.edge_paired_share = share;
    if (share >= params.edges.wide_min_paired_share) return;
  }
  DenseRounds rounds_wide;
  const RegistrationResult wide = problem.refineFrom(start, params.edges.wide_gate_factor, rounds_wide);
  if (!wide.success) return;
  if (!out.pose.success) {
    out.pose = wide;
    out.rounds = rounds_wide;
    out.wide_edge_pose = true;
    return;
  }
  VisibilityCheck check_normal, check_wide;
  tbb::parallel_invoke([&] { check_normal = free_space(out.pose.T_target_source); },
                       [&] { check_wide = free_space(wide.T_target_source); });
  const bool take_wide = check_wide.passed != check_normal.passed
                             ? check_wide.passed
                             : check_wide.consistentShare() > check_normal.consistentShare();
  if (take_wide) {
    out.pose = wide;
    out.rounds = rounds_wide;
    out.wide_edge_pose = true;
  }
  out.check = take_wide ? check_wide : check_normal;
}

/// The slide scan of a pose that passes the free-space test and whose patch problem was
/// degenerate (slide_scan.h); and of a partial pose, along the target view's dominant plane: its
/// observed directions may rest on a few objects matched at a slid alignment, which a better
/// agreeing alignment along the plane shows.
void scanSlides(const DepthView& source, const DepthView& target, const DenseProblem& problem,
                const RegistrationResult& hypothesis, const RefineParams& params, const FreeSpaceTest& free_space,
                const DominantPlane* target_plane, Refinement& out) {
  const bool partial = out.pose.partial;
  if (!params.slide_scan.enabled || !((out.pose.success && hypothesis.degenerate) || partial)) return;
  std::optional<RegistrationResult> along_plane;
  if (partial) {
    const auto plane = target_plane ? std::optional<DominantPlane>(*target_plane) : dominantPlane(target.segmentation);
    if (!plane) return;
    along_plane = detail::planeSymmetries(plane->normal, plane->centroid, out.pose.scene_radius_m);
  }
  if (!out.check) out.check = free_space(out.pose.T_target_source);
  if (!out.check->passed) return;
  DenseRounds rounds_scan;
  const auto refine_from = [&](const Isometry3& start) { return problem.refineFrom(start, 1.0, rounds_scan); };
  detail::SlideScanOutcome scan =
      detail::scanSlide(source, target, along_plane ? *along_plane : hypothesis, out.pose.T_target_source, refine_from,
                        params.slide_scan, free_space, partial);
  out.slide = scan.report;
  if (!scan.report.moved) return;
  out.pose = std::move(scan.pose);
  out.check = std::move(scan.check);
  out.rounds = rounds_scan;
  out.wide_edge_pose = false;
}

}  // namespace

void validate(const RefineParams& p) {
  validate(p.dense);
  validate(p.pixels);
  validate(p.edges.terms);
  if (!(p.edges.wide_gate_factor == 0.0 || p.edges.wide_gate_factor >= 1.0) || !std::isfinite(p.edges.wide_gate_factor))
    throw Error("refine: edges.wide_gate_factor must be 0 (off) or finite and >= 1");
  if (!(p.edges.wide_min_paired_share >= 0.0 && p.edges.wide_min_paired_share <= 1.0))
    throw Error("refine: edges.wide_min_paired_share must be in [0, 1]");
  validate(p.solver);
  validate(p.slide_scan);
}

Refinement refine(const DepthView& source, const DepthView& target, const RegistrationResult& hypothesis,
                  const std::vector<PatchCorrespondence>& inliers, const RefineParams& params,
                  const FreeSpaceTest& free_space, const DominantPlane* target_plane,
                  const EdgeTargets* target_edges) {
  const DenseProblem problem(source, target, hypothesis, inliers, params, target_edges);
  Refinement out;
  out.pose = problem.refineFrom(hypothesis.T_target_source, 1.0, out.rounds);
  widenEdges(problem, hypothesis.T_target_source, params, free_space, out);
  scanSlides(source, target, problem, hypothesis, params, free_space, target_plane, out);
  // The hypothesis's inlier bookkeeping goes with whichever pose is kept.
  out.pose.inliers = hypothesis.inliers;
  out.pose.num_inliers = hypothesis.num_inliers;
  out.pose.ransac_iterations = hypothesis.ransac_iterations;
  out.pose.ransac_ms = hypothesis.ransac_ms;
  out.pose.refine_ms = hypothesis.refine_ms;
  return out;
}

}  // namespace gasp
