#include "dense_refinement.h"

#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>

#include "gasp/core/depth_image.h"
#include "gasp/pipeline/edge_terms.h"
#include "gasp/pipeline/projective_terms.h"
#include "gasp/pipeline/step_extrapolation.h"
#include "gasp/pipeline/truncated_score.h"
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
  // One refinement from `start`: the rounds of dense_gates_m, then more at the last gate until a
  // round moves the source patches by less than dense_converged_m (RMS) or dense_max_rounds are
  // run. Edge gates are edge_gate_factor times the pixel gates. Fills `rounds`.
  const auto gateOfRound = [&](int round) {
    return params.dense_gates_m[std::min<std::size_t>(static_cast<std::size_t>(round), params.dense_gates_m.size() - 1)];
  };
  const int max_rounds = std::max(params.dense_rounds, params.dense_max_rounds);
  std::vector<Eigen::Vector3d> centroids;  // source patch centroids: a round's step is their RMS displacement
  for (const auto& p : source.segmentation.patches)
    if (p.centroid.allFinite()) centroids.push_back(p.centroid);
  const auto centroidsAt = [&](const Isometry3& T) {
    std::vector<Eigen::Vector3d> mapped;
    mapped.reserve(centroids.size());
    for (const auto& c : centroids) mapped.push_back(T * c);
    return mapped;
  };
  const auto rmsStep = [&](const Isometry3& before, const Isometry3& after) {
    if (centroids.empty()) return 0.0;
    double sum2 = 0;
    for (const auto& c : centroids) sum2 += (after * c - before * c).squaredNorm();
    return std::sqrt(sum2 / static_cast<double>(centroids.size()));
  };
  const int first_last_gate_round = static_cast<int>(params.dense_gates_m.size()) - 1;
  auto refineFrom = [&](const Isometry3& start, double edge_gate_factor, DenseRounds& rounds) {
    rounds = DenseRounds{};
    RegistrationResult pose = patch_pose;
    pose.T_target_source = start;
    const auto termsAt = [&](const Isometry3& T, int round) {
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
    RefinementParams refinement = params.pose.refinement;
    refinement.degeneracy = params.dense_degeneracy;
    std::optional<Isometry3> previous_step;  // the last round's motion, when it was a plain round at the last gate
    std::optional<GatedTerms> gathered_ahead;  // the terms at `pose`, when the line search gathered them
    RegistrationResult last_refined = pose;    // the last round's result (`pose` may be an extrapolated jump from it)
    for (int round = 0; round < max_rounds; ++round) {
      const GatedTerms gathered = gathered_ahead ? std::move(*gathered_ahead) : termsAt(pose.T_target_source, round);
      gathered_ahead.reset();
      rounds.terms = static_cast<int>(gathered.terms.size());
      rounds.run = round + 1;
      RegistrationResult next = refinePose(inliers, pose.T_target_source, refinement, gathered.terms);
      if (!next.success) {
        // The dense problem may be degenerate or fail where the patch problem was not: then no
        // pose is claimed (never a silently weaker one).
        next.reason = "dense refinement: " + next.reason;
        pose = next;
        break;
      }
      double step_m = rmsStep(pose.T_target_source, next.T_target_source);
      // Line search (truncated_score.h): at the last gate, a step longer than the round before
      // must not score worse against the terms gathered where it lands than the pose it leaves
      // against its own (an equal score is kept); it is halved up to dense_line_search_halvings
      // times, and when every length scores worse the rounds end at the last round's refined
      // pose. (Shrinking steps are left alone: there the rounds creep, and the extrapolation
      // below acts.)
      bool shortened = false;
      if (params.dense_line_search && round >= first_last_gate_round && step_m >= params.dense_converged_m &&
          rounds.last_step_m >= 0.0 && step_m > rounds.last_step_m) {
        const double score_before = truncatedScore(gathered, pose.T_target_source);
        const Isometry3 full_step = next.T_target_source * pose.T_target_source.inverse();
        Eigen::Vector3d centre = Eigen::Vector3d::Zero();
        for (const auto& c : centroidsAt(pose.T_target_source)) centre += c;
        if (!centroids.empty()) centre /= static_cast<double>(centroids.size());
        Isometry3 landing = next.T_target_source;
        GatedTerms there = termsAt(landing, round + 1);
        double score_after = truncatedScore(there, landing);
        double fraction = 1.0;
        for (int halving = 0; score_after < score_before && halving < params.dense_line_search_halvings; ++halving) {
          fraction *= 0.5;
          landing = stepPower(full_step, centre, fraction) * pose.T_target_source;
          there = termsAt(landing, round + 1);
          score_after = truncatedScore(there, landing);
        }
        const bool worse = score_after < score_before;
        std::optional<RegistrationResult> at;
        if (!worse && fraction < 1.0) {
          // A shortened step: the information, residuals and degeneracy are those at the pose returned.
          RefinementParams evaluate = refinement;
          evaluate.max_iterations = 0;
          at = refinePose(inliers, landing, evaluate, there.terms);
        }
        if (worse || (at && !at->success)) {
          // The rounds end at the last refined pose (not at an extrapolated jump from it).
          rounds.line_search_stopped = true;
          rounds.last_step_m = 0.0;
          pose = last_refined;
          break;
        }
        if (at) {
          next = std::move(*at);
          step_m = rmsStep(pose.T_target_source, next.T_target_source);
          ++rounds.shortened;
          shortened = true;
        }
        gathered_ahead = std::move(there);
      }
      const Isometry3 step = next.T_target_source * pose.T_target_source.inverse();
      rounds.last_step_m = step_m;
      pose = next;
      last_refined = pose;
      // A shortened step is no sign of convergence (the solve wanted to go further), nor a step
      // to extrapolate (it points where the full step was refused).
      if (shortened) {
        previous_step.reset();
        continue;
      }
      if (round + 1 >= params.dense_rounds && rounds.last_step_m < params.dense_converged_m) break;
      // Extrapolation (Besl & McKay 1992, IV-C; step_extrapolation.h): two rounds at the last
      // gate that move the pose the same way say it creeps; the next round starts ahead along the
      // last step. Never after the last round: the pose returned is always a refined one.
      if (round + 1 < params.dense_rounds || round + 1 >= max_rounds || params.dense_extrapolation_max <= 0.0) continue;
      if (!previous_step) {
        previous_step = step;
        continue;
      }
      const StepExtrapolation jump =
          extrapolateSteps(*previous_step, step, centroidsAt(pose.T_target_source), params.dense_extrapolation_max);
      if (jump.factor > 0.0) {
        pose.T_target_source = jump.jump * pose.T_target_source;
        previous_step.reset();
        gathered_ahead.reset();
      } else {
        previous_step = step;
      }
    }
    return pose;
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
