#include "gasp/pipeline/pair_registration.h"

#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <chrono>
#include <cstdio>
#include <map>
#include <memory>
#include <optional>

#include "gasp/core/error.h"
#include "gasp/core/stopwatch.h"
#include "gasp/pipeline/model_error.h"
#include "gasp/pipeline/pose_likelihood.h"
#include "gasp/pipeline/range_view.h"
#include "gasp/pipeline/symmetric_turns.h"
#include "gasp/superpixels/depth_superpixels.h"
#include "retry_policy.h"

namespace gasp {

void validate(const PairParams& p) {
  validate(p.segment);
  validate(p.associate);
  validate(p.hypothesise);
  validate(p.refine);
  validate(p.certify);
  validate(p.retry);
  validate(p.returns);
  validate(p.sweep_motion);
  validate(p.ground_search);
}

namespace {

/// Stage 4's outcome in the result.
void record(const Refinement& dense, double ms, PairResult& r) {
  r.pose = dense.pose;
  r.dense_unobservable = !r.pose.success && r.pose.degenerate;  // a partial pose included
  r.dense_terms = dense.rounds.terms;
  r.dense_rounds_run = dense.rounds.run;
  r.dense_last_step_m = dense.rounds.last_step_m;
  r.dense_steps_shortened = dense.rounds.shortened;
  r.dense_line_search_stopped = dense.rounds.line_search_stopped;
  r.wide_edge_pose = dense.wide_edge_pose;
  r.edge_paired_share = dense.edge_paired_share;
  r.slide = dense.slide;
  r.timings.dense_ms = ms;
}

/// Stage 5's verdict in the result.
void record(const Certificate& c, PairResult& r) {
  if (c.visibility) r.visibility = *c.visibility;
  r.visibility_refused = c.free_space_refused;
  r.edge_information = c.edge_information;
  if (!c.claimed) {
    r.pose.success = false;
    r.pose.partial = false;
    if (!c.reason.empty()) r.pose.reason = c.reason;
    if (c.free_directions.cols() > 0) {  // refused for its free directions: the set the reason names
      r.pose.degenerate = true;
      r.pose.unobservable_directions = c.free_directions;
    }
    return;
  }
  r.pose.success = !c.partial;
  r.pose.partial = c.partial;
  r.pose.degenerate = c.partial;
  if (!c.partial) return;
  r.pose.unobservable_directions = c.free_directions;
  r.pose.reason = c.reason;
}

/// The refine stage's parameters for this pair: partial rounds only where partial poses are claimed.
RefineParams refineParamsOf(const PairParams& p) {
  RefineParams out = p.refine;
  out.solver.partial_poses = out.solver.partial_poses && p.certify.partial_poses;
  return out;
}

/// r's correspondences at `indices` (RANSAC's inliers, or its alternative's).
std::vector<PatchCorrespondence> correspondencesAt(const PairResult& r, const std::vector<int>& indices) {
  std::vector<PatchCorrespondence> out;
  out.reserve(indices.size());
  for (int i : indices) out.push_back(r.correspondences[static_cast<std::size_t>(i)]);
  return out;
}

/// The view check (certify_stage.h) in r: its free directions, and its refusal when a view
/// cannot fix a pose (true: r holds the verdict).
bool refusedByViews(const ViewsCertificate& views, PairResult& r) {
  r.views_free_directions = static_cast<int>(views.source_free.cols() + views.target_free.cols());
  if (!views.refusal) return false;
  r.pose = *views.refusal;
  return true;
}

/// The certificate's uniqueness test on one alternative start: refined and certified like the
/// claimed pose in `r` (from `start`, anchored by `anchors`); the more likely of the two stays
/// claimed only when it is min_likelihood_ratio times more likely. `guided_support`: the
/// alternative's guided associations (-1: not verified that way).
void judgeAlternative(const DepthView& source, const DepthView& target, const RegistrationResult& start,
                      const std::vector<PatchCorrespondence>& anchors, int guided_support, const PairParams& p,
                      const RefineParams& refine_params, const FreeSpaceTest& free_space, const ViewsCertificate& views,
                      PairResult& r) {
  Refinement alternative = refine(source, target, start, anchors, refine_params, free_space,
                                  views.target_plane ? &*views.target_plane : nullptr);
  const Certificate c =
      certify(alternative.pose, alternative.rounds.terms, free_space, alternative.check, views, p.certify);
  Uniqueness u;
  if (c.claimed) {
    alternative.pose.success = !c.partial;
    alternative.pose.partial = c.partial;
    if (c.partial) alternative.pose.unobservable_directions = c.free_directions;
    u = compareAlternative(source, target, r.pose, alternative.pose, 2.0 * p.hypothesise.pose.ransac.inlier.distance_m,
                           p.certify);
  }
  if (!u.tested) return;
  r.uniqueness_log_ratio = u.log_ratio;
  if (u.take_alternative) {
    const PairTimings timings = r.timings;
    record(alternative, timings.dense_ms, r);
    record(c, r);
    r.timings = timings;
    r.alternative_taken = true;
    r.returns_refined = r.returns_fixed_free = false;  // the alternative is the cells' pose
    r.cells_reason.clear();
    r.uniqueness_log_ratio = -u.log_ratio;
    if (guided_support >= 0) r.guided_support = guided_support;
  } else if (u.refused) {
    Certificate refusal;
    refusal.reason = u.reason;
    record(refusal, r);
  }
}

/// The certificate's uniqueness test (certify_stage.h): the best distinct alternative RANSAC found
/// for hypothesis `h` must pass the guided verification as the hypothesis did, then is judged
/// (judgeAlternative).
void testUniqueness(const DepthView& source, const DepthView& target, const AssociatedViews& a, const Hypothesis& h,
                    const PairParams& p, const RefineParams& refine_params, const FreeSpaceTest& free_space,
                    const ViewsCertificate& views, PairResult& r) {
  const auto t0 = std::chrono::steady_clock::now();
  RegistrationResult start;
  start.success = true;
  start.T_target_source = *h.pose.alternative_T_target_source;
  start.inliers = h.pose.alternative_inliers;
  start.num_inliers = static_cast<int>(start.inliers.size());
  start.ransac_iterations = h.pose.ransac_iterations;
  start.ransac_ms = h.pose.ransac_ms;
  int guided_support = -1;
  if (p.hypothesise.guided.enabled) {
    guided_support = static_cast<int>(guidedAt(a, start.T_target_source, p.hypothesise.guided).size());
    if (guided_support < p.hypothesise.guided.min_support) {
      r.timings.certify_ms += msSince(t0);
      return;
    }
  }
  judgeAlternative(source, target, start, correspondencesAt(r, start.inliers), guided_support, p, refine_params, free_space,
                   views, r);
  r.timings.certify_ms += msSince(t0);
}

/// Stage 7 on a refused pose: the certificate refused the cells' pose in `r` for a direction their
/// terms leave free while both views' geometry fixes it (`refusal.not_aligned`), or, with
/// `returns_free_space`, on its free-space test. Where both views carry their returns, the returns'
/// rounds from it are claimed instead when they fix every direction, reach their pose again from
/// either side along their weakest translation (returnsBasin) and pass the certificate as a full
/// pose -- after a free-space refusal, with the free-space test on the returns
/// (returnsFreeSpace, these limits) instead of the binned cells', whose bins fall elsewhere in each
/// sweep. The tests after the certificate (uniqueness, symmetry) then judge it as any claimed
/// pose. Returns the cells' refused pose when the returns' pose replaced it (for restoring it
/// should a later test refuse theirs).
std::optional<RegistrationResult> fixOnTheReturns(const DepthView& source, const DepthView& target, const PairParams& p,
                                                  const FreeSpaceTest& free_space, const ViewsCertificate& views,
                                                  const Certificate& refusal,
                                                  const std::optional<VisibilityCheckParams>& returns_free_space,
                                                  PairResult& r) {
  const bool on_free_space = returns_free_space && refusal.free_space_refused && !refusal.not_aligned;
  if ((!refusal.not_aligned && !on_free_space) || !source.returns || !target.returns ||
      !r.pose.T_target_source.matrix().allFinite())
    return std::nullopt;
  const auto refused = [&r](const std::string& why) -> std::optional<RegistrationResult> {
    r.returns_reason = why;
    r.pose.reason += "; the returns' rounds from it: " + why;
    return std::nullopt;
  };
  auto t0 = std::chrono::steady_clock::now();
  const RegistrationResult q = refineOnReturns(*source.returns, *target.returns, r.pose.T_target_source, p.returns,
                                               p.refine.solver, target.superpixels.max_incidence_deg);
  r.timings.returns_ms += msSince(t0);
  if (!q.success) return refused(q.reason);
  // The certificate before the basin: its free-space test costs less than the basin's two restarts.
  const auto t1 = std::chrono::steady_clock::now();
  const FreeSpaceTest on_the_returns = [&](const Isometry3& T) {
    return returnsFreeSpace(*source.returns, *target.returns, T, *returns_free_space, p.refine.solver.noise_sigma_m,
                            target.superpixels.max_incidence_deg);
  };
  const Certificate c = certify(q, std::nullopt, on_free_space ? on_the_returns : free_space, std::nullopt, views, p.certify);
  r.timings.certify_ms += msSince(t1);
  if (!c.claimed || c.partial) return refused("their pose: " + (c.partial ? "partial, " + c.reason : c.reason));
  t0 = std::chrono::steady_clock::now();
  const ReturnsBasin basin =
      returnsBasin(*source.returns, *target.returns, q, p.returns, p.refine.solver, target.superpixels.max_incidence_deg);
  r.timings.returns_ms += msSince(t0);
  if (!basin.held) return refused(basin.reason);
  std::optional<RegistrationResult> cells = r.pose;
  r.cells_reason = r.pose.reason;
  r.pose.T_target_source = q.T_target_source;
  r.pose.information = q.information;
  r.pose.information_eigenvalues = q.information_eigenvalues;
  r.pose.success = false;  // record() claims it
  r.pose.degenerate = false;
  r.pose.unobservable_directions.resize(6, 0);
  r.pose.reason.clear();
  record(c, r);
  r.returns_refined = true;
  r.returns_fixed_free = true;
  r.returns_reason.clear();
  return cells;
}

/// The patch pairs RANSAC would count as inliers at a pose: the dense rounds' anchors when no
/// RANSAC ran (the tracking path, the symmetry test's turns).
ProjectiveTermParams inlierPairParams(const PairParams& p) {
  ProjectiveTermParams pairs;
  pairs.max_distance_m = p.hypothesise.pose.ransac.inlier.distance_m;
  pairs.max_normal_angle_deg = p.hypothesise.pose.ransac.inlier.normal_angle_deg;
  return pairs;
}

/// The certificate's symmetry test (CertifyParams::symmetry_test): the claimed full pose in `r`
/// against each of its symmetric turns refined by the dense rounds (anchored, as the tracking path,
/// by the patch pairs RANSAC would count as inliers there); the first turn that explains the views
/// better refuses it. For two sweeps carrying their returns, a turn the binned cells find better
/// is judged again on the returns (compareAlternativeOnReturns), the claimed pose and the turn
/// each refined by the returns' rounds: a binned cell is the mean of different returns in each
/// sweep, so where the cells find the turn better, the returns decide, and the claimed pose must
/// explain them better as the uniqueness test asks (its ratio and standard errors).
void testSymmetries(const DepthView& source, const DepthView& target, const PairParams& p,
                    const RefineParams& refine_params, const FreeSpaceTest& free_space, const ViewsCertificate& views,
                    PairResult& r) {
  const auto t0 = std::chrono::steady_clock::now();
  const ProjectiveTermParams pairs = inlierPairParams(p);
  const double distinct_m = 2.0 * p.hypothesise.pose.ransac.inlier.distance_m;
  // The turns refined and compared concurrently (one TBB task each), then taken in their order.
  const std::vector<SymmetricTurn> turns = symmetricTurns(source, target, r.pose.T_target_source);
  // The claimed pose's side of every comparison, computed once.
  const PoseSamples claimed = turns.empty() ? PoseSamples{} : samplesForComparison(source, target, r.pose, p.certify);
  std::vector<Uniqueness> compared(turns.size());
  std::vector<RegistrationResult> refined(turns.size());
  tbb::parallel_for(std::size_t{0}, turns.size(), [&](std::size_t k) {
    RegistrationResult start;
    start.success = true;
    start.T_target_source = turns[k].T_target_source;
    const Refinement alternative =
        refine(source, target, start, projectivePatchPairs(source, target, start.T_target_source, pairs), refine_params,
               free_space, views.target_plane ? &*views.target_plane : nullptr);
    RegistrationResult a = alternative.pose;
    if (!a.T_target_source.matrix().allFinite()) return;
    a.success = true;  // compared whether its own certificate would claim it or not
    a.partial = false;
    compared[k] = compareAlternative(source, target, r.pose, a, distinct_m, p.certify, claimed);
    refined[k] = a;
  });
  const bool on_returns = source.returns && target.returns;
  const double max_incidence_deg = target.superpixels.max_incidence_deg;
  // The returns' pose of `pose` (itself when their rounds fail).
  const auto returnsPose = [&](RegistrationResult pose) {
    const RegistrationResult q = refineOnReturns(*source.returns, *target.returns, pose.T_target_source, p.returns,
                                                 p.refine.solver, max_incidence_deg);
    if (q.success) pose.T_target_source = q.T_target_source;
    return pose;
  };
  std::optional<RegistrationResult> claimed_on_returns;
  for (std::size_t k = 0; k < turns.size(); ++k) {
    const SymmetricTurn& turn = turns[k];
    const Uniqueness& u = compared[k];
    if (!u.tested || !(u.log_ratio < 0.0)) continue;
    char reason[360];
    std::snprintf(reason, sizeof reason,
                  "symmetry: the pose turned %d deg about the target's axis (%.2f, %.2f, %.2f) explains the views "
                  "better (log-likelihood ratio %.1f)",
                  turn.degrees, turn.axis.x(), turn.axis.y(), turn.axis.z(), u.log_ratio);
    if (on_returns) {
      if (!claimed_on_returns) claimed_on_returns = r.returns_refined ? r.pose : returnsPose(r.pose);
      const Uniqueness v = compareAlternativeOnReturns(source, target, *claimed_on_returns, returnsPose(refined[k]),
                                                       distinct_m, p.certify, p.refine.solver.noise_sigma_m,
                                                       max_incidence_deg);
      // Told apart in the claimed pose's favour, or the turn's returns' pose is the claimed one;
      // when no return lands under both, the cells' verdict stands.
      if (v.tested ? !v.refused && !v.take_alternative : !(v.distance_m > distinct_m)) continue;
      if (v.tested)
        std::snprintf(reason, sizeof reason,
                      "symmetry: the pose turned %d deg about the target's axis (%.2f, %.2f, %.2f) explains the "
                      "binned cells better (log-likelihood ratio %.1f), and the returns do not favour the claimed "
                      "pose by the uniqueness test's margin (%.1f +- %.1f)",
                      turn.degrees, turn.axis.x(), turn.axis.y(), turn.axis.z(), u.log_ratio, v.log_ratio,
                      v.standard_error);
    }
    Certificate refusal;
    refusal.reason = reason;
    record(refusal, r);
    break;
  }
  r.timings.certify_ms += msSince(t0);
}

/// Stages 4-5 and the tests after the certificate, from the start in r.pose: `h` is association's
/// hypothesis (unverified when another stands in), `runner_up` the ground search's distinct
/// runner-up. `finer`: the views of the finer-scale retry.
void claimFrom(const DepthView& source, const DepthView& target, const PairParams& p, bool finer,
               const ViewsCertificate& views, const AssociatedViews& a, const Hypothesis& h,
               const std::optional<Isometry3>& runner_up, PairResult& r) {
  // A pose from a fallback hypothesis set (one-way partners, the finer scale) faces the fallback
  // limit. The ground search's does not: its look-alikes are judged by the uniqueness test on its
  // runner-up.
  const FreeSpaceTest free_space = freeSpaceTest(source, target, p.certify, finer || r.used_one_way);
  std::optional<Refinement> dense;
  const RefineParams refine_params = refineParamsOf(p);
  if (p.refine.dense.rounds > 0) {
    const auto t0 = std::chrono::steady_clock::now();
    // RANSAC's inliers stay in the dense problem, anchoring it where pixels are few.
    dense = refine(source, target, r.pose, correspondencesAt(r, r.pose.inliers), refine_params, free_space,
                   views.target_plane ? &*views.target_plane : nullptr);
    record(*dense, msSince(t0), r);
  }
  const auto t1 = std::chrono::steady_clock::now();
  const Certificate certificate = certify(r.pose, dense ? std::optional<int>(dense->rounds.terms) : std::nullopt, free_space,
                                          dense ? dense->check : std::nullopt, views, p.certify);
  record(certificate, r);
  r.timings.certify_ms = msSince(t1);
  const std::optional<RegistrationResult> cells_refused =
      dense ? fixOnTheReturns(source, target, p, free_space, views, certificate, visibilityLimits(p.certify, finer || r.used_one_way), r)
            : std::nullopt;
  if (r.pose.estimated() && dense && h.verified && h.pose.alternative_T_target_source &&
      p.certify.min_likelihood_ratio > 0.0)
    testUniqueness(source, target, a, h, p, refine_params, free_space, views, r);
  if (r.pose.estimated() && dense && runner_up && p.certify.min_likelihood_ratio > 0.0) {
    const auto t2 = std::chrono::steady_clock::now();
    RegistrationResult start;
    start.success = true;
    start.T_target_source = *runner_up;
    judgeAlternative(source, target, start, {}, -1, p, refine_params, free_space, views, r);
    r.timings.certify_ms += msSince(t2);
  }
  if (r.pose.success && dense && p.certify.symmetry_test && p.certify.min_likelihood_ratio > 0.0)
    testSymmetries(source, target, p, refine_params, free_space, views, r);
  if (cells_refused && r.returns_fixed_free && !r.pose.success) {  // the returns' pose refused after all: the cells' refusal stands
    r.returns_reason = "their pose: " + r.pose.reason;
    r.pose = *cells_refused;
    r.pose.reason += "; the returns' rounds from it: " + r.returns_reason;
    r.returns_refined = r.returns_fixed_free = false;
    r.cells_reason.clear();
  }
  if (!r.pose.success || !p.hypothesise.guided.enabled) return;
  // The verified associations: the guided ones at the claimed pose.
  if (!dense && !p.hypothesise.guided.densify) {
    r.verified = h.guided;
    return;
  }
  const auto t2 = std::chrono::steady_clock::now();
  r.verified = guidedAt(a, r.pose.T_target_source, p.hypothesise.guided);
  r.timings.guided_ms += msSince(t2);
}

/// The ground search (ground_search.h) for two sweeps whose association gave no claimed pose:
/// `refused` is that result. Its best pose is claimed from as association's hypothesis is, its
/// runner-up judged as RANSAC's alternative is. Either the search's claimed pose, or `refused`
/// with the search's reason and time added (association's verdicts, such as a free-space refusal
/// or a free direction, stay what the callers and the finer-scale retry read).
PairResult claimFromGroundSearch(const DepthView& source, const DepthView& target, const PairParams& p,
                                 const ViewsCertificate& views, const AssociatedViews& a, PairResult refused) {
  const GroundSearchResult g = groundSearch(*source.returns, *target.returns, p.ground_search);
  refused.timings.ground_search_ms = g.ms;
  if (!g.found) {
    refused.pose.reason += "; " + g.reason;
    return refused;
  }
  const auto t0 = std::chrono::steady_clock::now();
  PairResult r;
  r.association = refused.association;
  r.views_free_directions = refused.views_free_directions;
  r.ground_search = true;
  r.pose.T_target_source = g.T_target_source;
  claimFrom(source, target, p, false, views, a, Hypothesis{}, g.runner_up, r);
  if (!r.pose.estimated()) {
    refused.pose.reason += "; from the ground search: " + r.pose.reason;
    refused.timings.ground_search_ms += msSince(t0);  // the search's pose refined and judged
    return refused;
  }
  PairTimings total = refused.timings;
  total.addStages(r.timings);
  r.timings = total;
  return r;
}

/// Stages 2-5 on the views as segmented. `finer`: the views of the finer-scale retry (mutual
/// associations only; its poses face the fallback limit). Association's hypothesis, or where it
/// gives none the views' dominant planes (views that leave directions free); for two sweeps, the
/// ground search where neither gives a claimed pose.
PairResult registerAtScale(const DepthView& source, const DepthView& target, const PairParams& p, bool finer) {
  PairResult r;
  const ViewsCertificate views = certifyViews(source, target, p.certify);  // can these views fix a pose at all?
  if (refusedByViews(views, r)) return r;
  const AssociatedViews a = associate(source, target, p.associate);
  r.association = a.result;
  r.timings.association_ms = a.ms;
  Hypothesis h;
  if (a.result.associations.empty() && a.result.one_way.empty())
    r.pose.reason = "no associations: " + a.result.reason;
  else
    h = detail::hypothesiseWithFallback(a, p.hypothesise, p.retry.one_way_fallback && !finer, r);
  const bool searchable = !finer && source.returns && target.returns && p.ground_search.enabled;
  if (h.verified) {
    claimFrom(source, target, p, finer, views, a, h, std::nullopt, r);
    if (r.pose.estimated() || !searchable) return r;
    return claimFromGroundSearch(source, target, p, views, a, std::move(r));
  }
  // Views that leave directions free: their dominant planes fix the others (plane_hypothesis.h).
  const auto T = views.source_plane && views.target_plane ? planeHypothesis(*views.source_plane, *views.target_plane)
                                                          : std::nullopt;
  if (T) {
    std::string no_hypothesis = std::move(r.pose.reason);
    r.pose = RegistrationResult{};
    r.pose.T_target_source = *T;
    r.plane_hypothesis = true;
    claimFrom(source, target, p, finer, views, a, h, std::nullopt, r);
    if (!r.pose.estimated()) r.pose.reason = no_hypothesis + "; from the views' dominant planes: " + r.pose.reason;
    if (r.pose.estimated() || !searchable) return r;
  }
  return searchable ? claimFromGroundSearch(source, target, p, views, a, std::move(r)) : r;
}

/// The returns' pose `q` of a claimed pose judged by its basin (returnsBasin): restarted half the
/// first gate either side along their weakest translation, each restart's end is compared with it
/// on the returns (compareAlternativeOnReturns).
/// - A restart drawn farther from the pose than it started has found another minimum: the pose
///   stands only when that minimum explains the returns no better.
/// - A restart that ends nearer than it started was drawn back (the returns hold the pose, or
///   leave that direction flat, where the cells' fix stands); a failed restart found no minimum.
/// - The end that explains the returns best, when better by the uniqueness test's margin, is taken
///   instead (refined again, as the restarts stop coarser): its own basin must hold and it must pass
///   the free-space test on the returns (`limits`).
/// Otherwise (another minimum better by less than the margin, a taken end that fails): nullopt,
/// the reason in `why`.
std::optional<RegistrationResult> heldBasin(const DepthView& source, const DepthView& target, const PairParams& p,
                                            const VisibilityCheckParams& limits, const RegistrationResult& q,
                                            std::string& why) {
  const double incidence = target.superpixels.max_incidence_deg, other_minimum_m = p.returns.gates_m.back();
  // The restarts only tell which minimum the rounds end in: every other return, converged when
  // they move less than a tenth of the basin's tolerance (a taken end is refined again in full).
  ReturnsRefineParams restart = p.returns;
  restart.return_step = 2;
  restart.converged_m = std::max(restart.converged_m, 0.1 * restart.basin_tolerance_m);
  const ReturnsBasin basin = returnsBasin(*source.returns, *target.returns, q, restart, p.refine.solver, incidence);
  if (basin.held) return q;
  why = basin.reason;
  // Both ends compared first: the likeliest by the margin is taken; otherwise a likelier minimum
  // that a restart was drawn away to refuses the pose.
  std::optional<RegistrationResult> better;
  double best_ratio = 0.0;
  std::string refusal;
  for (const RegistrationResult& end : basin.ends) {
    if (!end.success) continue;  // found no minimum (a degenerate solve where the returns leave a direction flat)
    const Uniqueness v = compareAlternativeOnReturns(source, target, q, end, other_minimum_m, p.certify,
                                                     p.refine.solver.noise_sigma_m, incidence);
    const bool drawn_away =
        (end.T_target_source.translation() - q.T_target_source.translation()).norm() > restart.basin_offset_m;
    if (!v.tested && (!drawn_away || v.distance_m <= other_minimum_m)) continue;  // the same minimum
    if (!v.tested) {
      refusal = "; no return lands under both poses";
    } else if (v.take_alternative) {
      if (v.log_ratio < best_ratio) best_ratio = v.log_ratio, better = end;
    } else if (drawn_away && v.log_ratio < 0.0) {
      char text[200];
      std::snprintf(text, sizeof text,
                    "; that end explains the returns better (log-likelihood ratio %.1f +- %.1f), short of the "
                    "uniqueness test's margin",
                    v.log_ratio, v.standard_error);
      refusal = text;
    }
  }
  if (!better) {
    if (refusal.empty()) return q;  // the likeliest of the minima found
    why += refusal;
    return std::nullopt;
  }
  const RegistrationResult taken =
      refineOnReturns(*source.returns, *target.returns, better->T_target_source, p.returns, p.refine.solver, incidence);
  if (!taken.success) {
    why += "; the rounds from the likelier end: " + taken.reason;
    return std::nullopt;
  }
  const VisibilityCheck free_space = returnsFreeSpace(*source.returns, *target.returns, taken.T_target_source, limits,
                                                      p.refine.solver.noise_sigma_m, incidence);
  if (!free_space.passed) {
    why += "; the likelier end: " + free_space.reason;
    return std::nullopt;
  }
  const ReturnsBasin its_own =
      returnsBasin(*source.returns, *target.returns, taken, restart, p.refine.solver, incidence);
  if (!its_own.held) {
    why = "their pose taken from a restart: " + its_own.reason;
    return std::nullopt;
  }
  return taken;
}

/// Stage 7 in the result: when a full pose is claimed and both views carry their returns, the
/// returns' rounds from it; their pose and information replace the cells' when they succeed. With
/// `judge_basin` (a pose found without a prior), their pose must be the likeliest of the minima
/// their restarts find (heldBasin), or there is no estimate: the cells' claimed pose can lie off
/// the truth by more than the returns' first gate along a direction the cells barely fix (a floor
/// at grazing incidence), and the returns' rounds then settle in a minimum of their own there.
void refineOnTheReturns(const DepthView& source, const DepthView& target, const PairParams& p, bool judge_basin,
                        PairResult& r) {
  if (!r.pose.success || r.returns_refined || !source.returns || !target.returns) return;
  const auto t0 = std::chrono::steady_clock::now();
  RegistrationResult refined = refineOnReturns(*source.returns, *target.returns, r.pose.T_target_source, p.returns,
                                               p.refine.solver, target.superpixels.max_incidence_deg);
  if (refined.success && judge_basin && p.certify.min_likelihood_ratio > 0.0) {
    std::string why;
    const std::optional<RegistrationResult> held =
        heldBasin(source, target, p, visibilityLimits(p.certify, r.used_one_way || r.retried), refined, why);
    if (!held) {
      r.timings.returns_ms += msSince(t0);
      r.returns_reason = why;
      r.pose.success = false;
      r.pose.partial = false;
      r.pose.reason = "the returns' rounds from the claimed pose: " + why;
      r.edge_information.setZero();
      r.verified.clear();
      return;
    }
    refined = *held;
  }
  r.timings.returns_ms += msSince(t0);
  if (!refined.success) {
    r.returns_reason = refined.reason;
    return;
  }
  r.returns_refined = true;
  r.pose.T_target_source = refined.T_target_source;
  r.pose.information = refined.information;
  r.pose.information_eigenvalues = refined.information_eigenvalues;
  r.edge_information = informationWithModelError(refined.information, p.certify.model_error);
}

/// Stage 6's finer scale for one pair: `r` is the default scale's result.
PairResult retryAtFinerScale(const DepthView& source, const DepthView& target, const PairParams& p, PairResult r) {
  const double f = p.retry.finer_area_factor;
  const auto t0 = std::chrono::steady_clock::now();
  auto views = std::make_shared<std::pair<DepthView, DepthView>>();
  try {
    tbb::parallel_invoke([&] { views->first = detail::finerScaleView(source, f); },
                         [&] { views->second = detail::finerScaleView(target, f); });
  } catch (const std::exception& e) {  // e.g. a depth image that does not match its intrinsics
    r.retried = true;
    r.timings.retry_segmentation_ms = msSince(t0);
    r.pose.reason += "; " + detail::finerScaleReason(f, std::string("segmentation failed: ") + e.what());
    return r;
  }
  const double segmentation_ms = msSince(t0);
  PairResult retry = registerAtScale(views->first, views->second, p, true);
  PairTimings total = r.timings;
  total.addStages(retry.timings);
  total.retry_segmentation_ms = segmentation_ms;
  if (retry.pose.success || (retry.pose.partial && !r.pose.partial)) {  // a full pose, else a partial one
    retry.retried = retry.finer_scale = true;
    retry.retry_views = std::move(views);
    retry.timings = total;
    return retry;
  }
  r.retried = true;
  r.timings = total;
  if (!r.pose.partial) r.pose.reason += "; " + detail::finerScaleReason(f, retry.pose.reason);
  r.visibility_refused = r.visibility_refused || retry.visibility_refused;
  return r;
}

/// Stage 8 (sweep_motion.h): for two timed sweeps with a claimed pose, their motions estimated
/// from it; moving sweeps are deskewed with their twists and registered again (without stage 8),
/// and that registration, of the deskewed sweeps' views, becomes the result. Sweeps at rest
/// whose pose the motions the test cannot exclude leave undetermined get no estimate.
void sweepMotionStage(const DepthView& source, const DepthView& target, const PairParams& p, PairResult& r) {
  if (!p.sweep_motion.enabled || !r.pose.success || !source.returns || !target.returns ||
      !sweepTimed(source.returns->scan()) || !sweepTimed(target.returns->scan()))
    return;
  const auto t0 = std::chrono::steady_clock::now();
  SweepMotion m = estimateSweepMotion(*source.returns, *target.returns, r.pose.T_target_source, p.returns,
                                      p.refine.solver, p.sweep_motion, target.superpixels.max_incidence_deg);
  const auto asRead = [&] {  // the pose as read stays, with the verdict
    r.sweep_motion = std::move(m);
    r.timings.sweep_motion_ms += msSince(t0);
  };
  if (!m.moving) {
    if (!m.determined) {  // at rest, but a motion the test cannot exclude could move the pose
      r.pose.success = false;
      r.pose.reason = m.reason;
    }
    return asRead();
  }
  auto deskewed = std::make_shared<std::pair<DepthView, DepthView>>();
  try {
    tbb::parallel_invoke(
        [&] {
          deskewed->first = makeRangeView(deskewSweep(source.returns->scan(), m.source_twist), source.superpixels, p.returns);
        },
        [&] {
          deskewed->second = makeRangeView(deskewSweep(target.returns->scan(), m.target_twist), target.superpixels, p.returns);
        });
  } catch (const std::exception& e) {  // with why it was not deskewed
    m.moving = false;
    m.reason = std::string("sweep motion: the deskewed sweeps' views failed: ") + e.what();
    return asRead();
  }
  const double own_ms = msSince(t0);  // the test, the estimate and the deskewed views
  PairParams once = p;
  once.sweep_motion.enabled = false;
  PairResult again = registerViews(deskewed->first, deskewed->second, once);
  again.timings.addStages(r.timings);  // the first registration's stages, beside the second's
  again.timings.retry_segmentation_ms += r.timings.retry_segmentation_ms;
  again.timings.sweep_motion_ms += own_ms;
  if (!again.retry_views) again.retry_views = std::move(deskewed);
  char buf[160];
  std::snprintf(buf, sizeof buf, "the sweeps deskewed with their motion (score F %.2f over %d sectors): ", m.score_f,
                m.sectors);
  if (!again.pose.success) again.pose.reason = buf + again.pose.reason;
  again.sweep_motion = std::move(m);
  r = std::move(again);
}

bool retryApplies(const PairResult& r, const DepthView& source, const DepthView& target, const PairParams& p) {
  return p.retry.finer_area_factor > 0.0 && detail::finerScaleRetryApplies(r, source, target);
}

}  // namespace

PairResult registerViews(const DepthView& source, const DepthView& target, const PairParams& params) {
  validate(params);
  PairResult r = registerAtScale(source, target, params, false);
  if (retryApplies(r, source, target, params)) r = retryAtFinerScale(source, target, params, std::move(r));
  refineOnTheReturns(source, target, params, true, r);  // a retry's views carry the same returns
  sweepMotionStage(source, target, params, r);
  return r;
}

PairResult trackViews(const DepthView& source, const DepthView& target, const Isometry3& T_target_source_predicted,
                      const PairParams& p, const EdgeTargets* target_edges) {
  validate(p);
  PairResult r;
  const ViewsCertificate views = certifyViews(source, target, p.certify);
  if (refusedByViews(views, r)) return r;
  if (p.refine.dense.rounds == 0) {
    r.pose.reason = "tracking: no dense rounds (refine.dense_rounds 0)";
    return r;
  }
  RegistrationResult start;
  start.success = true;
  start.T_target_source = T_target_source_predicted;
  const FreeSpaceTest free_space = freeSpaceTest(source, target, p.certify, false);
  const auto t0 = std::chrono::steady_clock::now();
  // The patch pairs RANSAC would count as inliers at the prediction stand in for its inliers.
  const ProjectiveTermParams pairs = inlierPairParams(p);
  const Refinement dense = refine(source, target, start, projectivePatchPairs(source, target, start.T_target_source, pairs),
                                  refineParamsOf(p), free_space, views.target_plane ? &*views.target_plane : nullptr,
                                  target_edges);
  record(dense, msSince(t0), r);
  const auto t1 = std::chrono::steady_clock::now();
  const Certificate certificate = certify(r.pose, dense.rounds.terms, free_space, dense.check, views, p.certify);
  record(certificate, r);
  r.timings.certify_ms = msSince(t1);
  // A free-space refusal stands here: odometry reads it as a scene change.
  fixOnTheReturns(source, target, p, free_space, views, certificate, std::nullopt, r);
  refineOnTheReturns(source, target, p, false, r);  // from a prediction
  return r;
}

PairResult registerViews(const DepthView& source, const DepthView& target) {
  static const PairParams defaults;
  return registerViews(source, target, defaults);
}

PairResult registerDepthImages(const cv::Mat& source_depth_m, const cv::Mat& target_depth_m,
                               const CameraIntrinsics& intrinsics, const PairParams& params) {
  validate(params);
  const auto views = makeDepthViews(source_depth_m, target_depth_m, intrinsics, params.segment);
  return registerViews(views.first, views.second, params);
}

std::pair<const DepthView*, const DepthView*> viewsOf(const PairResult& r, const DepthView& source,
                                                      const DepthView& target) {
  if (r.retry_views) return {&r.retry_views->first, &r.retry_views->second};
  return {&source, &target};
}

namespace {

/// Whether `c` is a better registration of a view set than `best` (ViewSetResult::best).
bool better(const ViewSetRegistration& c, const ViewSetRegistration* best) {
  if (!best) return true;
  const bool cs = c.result.pose.success, bs = best->result.pose.success;
  if (cs != bs) return cs;
  const bool cp = c.result.pose.partial, bp = best->result.pose.partial;  // then partial over none
  if (cp != bp) return cp;
  if (cs && c.finer_scale != best->finer_scale) return !c.finer_scale;
  return c.result.pose.num_inliers > best->result.pose.num_inliers;
}

/// The finer-scale views of a view set, each segmented at most once (nullopt: it failed).
class FinerViews {
 public:
  FinerViews(const std::vector<const DepthView*>& views, double factor, const char* name, std::vector<std::string>& notes)
      : views_(views), factor_(factor), name_(name), notes_(notes) {}
  const std::optional<DepthView>& at(std::size_t k) {
    auto it = cache_.find(k);
    if (it != cache_.end()) return it->second;
    std::optional<DepthView> v;
    try {
      v = detail::finerScaleView(*views_[k], factor_);
    } catch (const std::exception& e) {
      notes_.push_back(std::string(name_) + " view " + std::to_string(k) + ": " +
                       detail::finerScaleReason(factor_, std::string("segmentation failed: ") + e.what()));
    }
    return cache_.emplace(k, std::move(v)).first->second;
  }

 private:
  const std::vector<const DepthView*>& views_;
  double factor_;
  const char* name_;
  std::vector<std::string>& notes_;
  std::map<std::size_t, std::optional<DepthView>> cache_;
};

}  // namespace

ViewSetResult registerViewSets(const std::vector<const DepthView*>& sources,
                               const std::vector<const DepthView*>& targets, const PairParams& params) {
  validate(params);
  for (const auto* views : {&sources, &targets})
    for (const DepthView* v : *views)
      if (!v) throw Error("registerViewSets: a null view pointer");
  ViewSetResult out;
  std::vector<std::size_t> retry;  // registrations the finer scale may turn into an estimate
  bool any_pose = false;
  for (std::size_t t = 0; t < targets.size(); ++t)
    for (std::size_t s = 0; s < sources.size(); ++s) {
      ViewSetRegistration reg{s, t, registerAtScale(*sources[s], *targets[t], params, false), false};
      any_pose = any_pose || reg.result.pose.success;
      if (retryApplies(reg.result, *sources[s], *targets[t], params)) retry.push_back(out.registrations.size());
      out.registrations.push_back(std::move(reg));
    }
  if (!any_pose && !retry.empty()) {
    const double f = params.retry.finer_area_factor;
    FinerViews fine_sources(sources, f, "source", out.notes), fine_targets(targets, f, "target", out.notes);
    for (std::size_t k : retry) {
      const std::size_t s = out.registrations[k].source, t = out.registrations[k].target;
      const auto& target = fine_targets.at(t);
      const auto& source = fine_sources.at(s);
      if (!source || !target) continue;
      ViewSetRegistration reg{s, t, registerAtScale(*source, *target, params, true), true};
      reg.result.retried = reg.result.finer_scale = true;
      if (!reg.result.pose.success) reg.result.pose.reason = detail::finerScaleReason(f, reg.result.pose.reason);
      out.registrations.push_back(std::move(reg));
    }
  }
  const auto chooseBest = [&out] {
    out.best = -1;
    for (std::size_t k = 0; k < out.registrations.size(); ++k)
      if (better(out.registrations[k], out.best < 0 ? nullptr : &out.registrations[static_cast<std::size_t>(out.best)]))
        out.best = static_cast<int>(k);
  };
  chooseBest();
  // Stage 7 for the one to use only (a finer-scale view carries its view's returns); the returns'
  // rounds from a refused pose ran in each pair's registerAtScale, since they decide which pairs
  // give an estimate. A pose the claimed pose's basin refuses gives way to the next best.
  while (out.best >= 0) {
    ViewSetRegistration& best = out.registrations[static_cast<std::size_t>(out.best)];
    if (!best.result.pose.success) break;
    refineOnTheReturns(*sources[best.source], *targets[best.target], params, true, best.result);
    if (best.result.pose.success) break;
    chooseBest();
  }
  return out;
}

}  // namespace gasp
