#include "dense_refinement.h"

#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>

#include "gasp/core/depth_image.h"
#include "gasp/pipeline/edge_terms.h"
#include "gasp/pipeline/projective_terms.h"
#include "gasp/pipeline/dense_rounds.h"
#include "gasp/pipeline/visibility_check.h"
#include "gasp/registration/refinement.h"
#include "slide_scan.h"

namespace gasp::detail {

namespace {

/// Source edge points that T maps in front of the target camera onto a pixel with valid depth.
int edgePointsInView(const EdgePoints& source, const DepthView& target, const Isometry3& T_target_source) {
  int n = 0;
  const cv::Mat& d = target.depth_m;
  for (const Eigen::Vector3d& p : source.points) {
    double u = 0, v = 0;
    if (!target.intrinsics.project(T_target_source * p, u, v)) continue;
    const int iu = static_cast<int>(std::lround(u)), iv = static_cast<int>(std::lround(v));
    if (iu < 0 || iv < 0 || iu >= d.cols || iv >= d.rows) continue;
    n += isValidDepth(d.at<float>(iv, iu)) ? 1 : 0;
  }
  return n;
}

}  // namespace

DenseOutcome refineDense(const DepthView& source, const DepthView& target, const RegistrationResult& patch_pose,
                         const std::vector<PatchCorrespondence>& inliers, const PairParams& params,
                         const VisibilityCheckParams& visibility) {
  // Edge terms: both views' edges found once per pair (the target's in a KD-tree).
  EdgePoints source_edges;
  std::unique_ptr<EdgeTargets> edge_targets;
  if (params.edge_terms) {
    tbb::parallel_invoke([&] { source_edges = findEdgePoints(source, params.edges); },
                         [&] { edge_targets = std::make_unique<EdgeTargets>(target, params.edges); });
  }
  // One refinement from `start` (dense_rounds.h): the rounds of dense_gates_m, then more at the
  // last gate until they converge. Edge gates are edge_gate_factor times the pixel gates.
  const auto gateOfRound = [&](int round) {
    return params.dense_gates_m[std::min<std::size_t>(static_cast<std::size_t>(round), params.dense_gates_m.size() - 1)];
  };
  std::vector<Eigen::Vector3d> centroids;  // source patch centroids: a round's step is their RMS displacement
  for (const auto& p : source.segmentation.patches)
    if (p.centroid.allFinite()) centroids.push_back(p.centroid);
  DenseRoundsSettings settings;
  settings.gates_m = params.dense_gates_m;
  settings.rounds = params.dense_rounds;
  settings.max_rounds = params.dense_max_rounds;
  settings.converged_m = params.dense_converged_m;
  settings.extrapolation_max = params.dense_extrapolation_max;
  settings.line_search = params.dense_line_search;
  settings.line_search_halvings = params.dense_line_search_halvings;
  RefinementParams refinement = params.pose.refinement;
  refinement.degeneracy = params.dense_degeneracy;
  RefinementParams evaluation = refinement;
  evaluation.max_iterations = 0;
  auto refineFrom = [&](const Isometry3& start, double edge_gate_factor, DenseRounds& rounds) {
    DenseRoundsOps ops;
    ops.gather = [&](const Isometry3& T, int round) {
      GatedTerms gathered;
      ProjectiveTermParams proj = params.projective;
      proj.max_distance_m = gateOfRound(round);
      gathered.terms = projectiveTerms(source, target, T, proj);
      gathered.pixel_terms = gathered.terms.size();
      gathered.pixel_gate_m = proj.max_distance_m;
      gathered.edge_gate_m = edge_gate_factor * proj.max_distance_m;
      if (edge_targets) {
        const auto more = edge_targets->terms(source_edges, T, gathered.edge_gate_m);
        gathered.terms.insert(gathered.terms.end(), more.begin(), more.end());
      }
      return gathered;
    };
    ops.solve = [&](const Isometry3& from, const std::vector<PointToPlane>& terms, bool evaluate_only) {
      return refinePose(inliers, from, evaluate_only ? evaluation : refinement, terms);
    };
    RegistrationResult first = patch_pose;
    first.T_target_source = start;
    return runDenseRounds(first, centroids, settings, ops, rounds);
  };
  auto refine = [&](double edge_gate_factor, DenseRounds& rounds) {
    return refineFrom(patch_pose.T_target_source, edge_gate_factor, rounds);
  };

  // The patch pose's inlier bookkeeping goes with whichever pose is returned.
  const auto finish = [&](DenseOutcome& o) {
    o.pose.inliers = patch_pose.inliers;
    o.pose.num_inliers = patch_pose.num_inliers;
    o.pose.ransac_iterations = patch_pose.ransac_iterations;
    o.pose.ransac_ms = patch_pose.ransac_ms;
    o.pose.refine_ms = patch_pose.refine_ms;
    return o;
  };
  DenseOutcome out;
  out.pose = refine(1.0, out.rounds);
  // The wide-edge second refinement and the selection between the two refinements.
  const auto widenEdges = [&] {
    // A slide larger than the pixel gates leaves most source edge points without a target edge
    // within the last gate -- or, where the planes alone cannot pin the slide, leaves the first
    // refinement degenerate. Then a second refinement with wider edge gates is run: when the first
    // failed, its pose is taken (the final visibility check still judges it); otherwise the pose
    // that passes the visibility check (with the caller's parameters) is kept, and when both or
    // neither pass, the one whose views agree more -- the larger share of consistent samples.
    // (Wide edge gates alone pair wrong edges in clutter.) Nothing to widen without target edges
    // with a direction or with weightless edge terms.
    if (!edge_targets || edge_targets->size() == 0 || params.edges.weight <= 0.0 || params.wide_edge_gate_factor <= 0.0 ||
        source_edges.points.empty() || params.dense_rounds == 0)
      return;
    if (out.pose.success) {
      // Of the source edge points that land on the target's depth: points outside its view can
      // have no partner, and a partial overlap alone must not call the second refinement.
      const int in_view = edgePointsInView(source_edges, target, out.pose.T_target_source);
      if (in_view == 0) return;
      const double last_gate = gateOfRound(params.dense_rounds - 1);
      const double paired =
          0.5 * static_cast<double>(edge_targets->terms(source_edges, out.pose.T_target_source, last_gate).size()) /
          static_cast<double>(in_view);
      out.edge_paired_share = std::min(1.0, paired);
      if (out.edge_paired_share >= params.wide_edge_min_paired_share) return;
    }
    DenseRounds rounds_wide;
    const RegistrationResult wide = refine(params.wide_edge_gate_factor, rounds_wide);
    if (!wide.success) return;
    if (!out.pose.success) {
      out.pose = wide;
      out.rounds = rounds_wide;
      out.wide_edge_pose = true;
      return;
    }
    VisibilityCheck check_normal, check_wide;
    tbb::parallel_invoke([&] { check_normal = checkVisibility(source, target, out.pose.T_target_source, visibility); },
                         [&] { check_wide = checkVisibility(source, target, wide.T_target_source, visibility); });
    const bool take_wide = check_wide.passed != check_normal.passed
                               ? check_wide.passed
                               : check_wide.consistentShare() > check_normal.consistentShare();
    if (take_wide) {
      out.pose = wide;
      out.rounds = rounds_wide;
      out.wide_edge_pose = true;
    }
    out.check = take_wide ? check_wide : check_normal;
  };
  widenEdges();

  // The slide scan (slide_scan.h): a claimed pose whose patch problem left directions
  // unobservable is checked for a slide along them.
  if (params.slide_scan.enabled && out.pose.success && patch_pose.degenerate && params.dense_rounds > 0) {
    if (!out.check) out.check = checkVisibility(source, target, out.pose.T_target_source, visibility);
    if (out.check->passed) {
      DenseRounds rounds_scan;
      const auto refine_from = [&](const Isometry3& start) { return refineFrom(start, 1.0, rounds_scan); };
      SlideScanOutcome scan =
          scanSlide(source, target, patch_pose, out.pose.T_target_source, refine_from, params.slide_scan, visibility);
      out.slide = scan.report;
      if (scan.report.moved) {
        out.pose = std::move(scan.pose);
        out.check = std::move(scan.check);
        out.rounds = rounds_scan;
        out.wide_edge_pose = false;
      }
    }
  }
  return finish(out);
}


}  // namespace gasp::detail
