#include "gasp/slam/relocalisation.h"

#include <Eigen/Cholesky>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "gasp/core/error.h"
#include "gasp/core/format.h"
#include "gasp/core/pose_perturbation.h"

namespace gasp {

namespace {

/// a then b: T = T_a T_b, S = S_a + Ad(T_a) S_b Ad(T_a)^T (left perturbations, first order).
RelativePoseEstimate then(const RelativePoseEstimate& a, const RelativePoseEstimate& b) {
  RelativePoseEstimate out;
  const Matrix6d Ad = adjoint(a.T_a_b);
  out.T_a_b = a.T_a_b * b.T_a_b;
  out.covariance = a.covariance + Ad * b.covariance * Ad.transpose();
  out.edges = a.edges + b.edges;
  return out;
}

/// The constraint as an estimate, from -> to or (inverted) to -> from.
RelativePoseEstimate estimateOf(const PoseConstraint& h, bool inverted) {
  RelativePoseEstimate e;
  e.T_a_b = h.T_from_to;
  e.covariance = covarianceOf(h);  // throws for an information that is not positive definite
  e.edges = 1;
  if (inverted) {
    // Exp(x) T -> T^-1 Exp(-x) = Exp(-Ad(T^-1) x) T^-1.
    e.T_a_b = h.T_from_to.inverse();
    const Matrix6d Ad = adjoint(e.T_a_b);
    e.covariance = Ad * e.covariance * Ad.transpose();
  }
  return e;
}

/// The largest set of mutually agreeing candidates 0..n-1 (agree: n x n, symmetric): a
/// depth-first branch and bound over the candidates in their order, so among sets of the largest
/// size the first in lexicographic order (the best-ranked candidates) is returned. n is small
/// (RelocalisationVotes::kMaxCandidates), so the exponential worst case stays bounded.
std::vector<std::size_t> largestAgreeingSet(const std::vector<char>& agree, std::size_t n) {
  std::vector<std::size_t> best, current;
  const auto extend = [&](const auto& self, const std::vector<std::size_t>& candidates) -> void {
    if (current.size() > best.size()) best = current;
    for (std::size_t c = 0; c < candidates.size(); ++c) {
      if (current.size() + (candidates.size() - c) <= best.size()) return;  // cannot beat the best
      const std::size_t i = candidates[c];
      std::vector<std::size_t> next;
      for (std::size_t d = c + 1; d < candidates.size(); ++d)
        if (agree[i * n + candidates[d]]) next.push_back(candidates[d]);
      current.push_back(i);
      self(self, next);
      current.pop_back();
    }
  };
  std::vector<std::size_t> all(n);
  for (std::size_t i = 0; i < n; ++i) all[i] = i;
  extend(extend, all);
  return best;
}

}  // namespace

std::optional<RelativePoseEstimate> predictThroughRelocalisation(const std::vector<PoseConstraint>& tree,
                                                                 std::size_t frame_count, const PoseConstraint& h,
                                                                 std::size_t from, std::size_t to) {
  // Either from ~ h.from and h.to ~ to, or from ~ h.to and h.from ~ to (~: a path in the tree).
  for (const bool inverted : {false, true}) {
    const std::size_t near_from = inverted ? h.to : h.from, near_to = inverted ? h.from : h.to;
    const auto first = composeAlongTree(tree, frame_count, from, near_from);
    if (!first) continue;
    const auto last = composeAlongTree(tree, frame_count, near_to, to);
    if (!last) continue;
    return then(then(*first, estimateOf(h, inverted)), *last);
  }
  return std::nullopt;
}

RelocalisationVotes::Decision RelocalisationVotes::offer(const PoseConstraint& c, std::size_t attempt,
                                                         const std::vector<PoseConstraint>& tree,
                                                         std::size_t frame_count,
                                                         const std::vector<std::size_t>& roots) {
  if (c.from >= roots.size() || c.to >= roots.size())
    throw Error("relocalisation " + std::to_string(c.from) + " -> " + std::to_string(c.to) + ": a frame out of range");
  Decision d;
  Matrix6d S_meas;
  try {
    S_meas = covarianceOf(c);
  } catch (const Error&) {
    d.reason = "its information is not positive definite: not a vote";
    return d;
  }
  const std::size_t needed = params_.relocalisation_agreeing;
  // The chi-square of `v` against the prediction through `h` (NaN when h cannot predict it).
  const auto chi2Of = [&](const PoseConstraint& h, const PoseConstraint& v, const Matrix6d& S_v) {
    const auto prediction = predictThroughRelocalisation(tree, frame_count, h, v.from, v.to);
    if (!prediction) return std::numeric_limits<double>::quiet_NaN();
    const Vector6d xi = leftPerturbation(v.T_from_to, prediction->T_a_b);
    return xi.dot((prediction->covariance + S_v).ldlt().solve(xi));
  };
  std::vector<std::pair<double, std::size_t>> agreeing;  // chi-square against c, position in waiting_
  if (needed > 1) {
    const auto samePieces = [&](const PoseConstraint& h) {
      const std::size_t a = roots[h.from], b = roots[h.to], x = roots[c.from], y = roots[c.to];
      return (a == x && b == y) || (a == y && b == x);
    };
    for (std::size_t i = 0; i < waiting_.size(); ++i) {
      const PoseConstraint& h = waiting_[i].constraint;
      if (!samePieces(h)) continue;
      const double chi2 = chi2Of(h, c, S_meas);
      if (std::isnan(chi2)) continue;
      if (!(chi2 >= d.chi2)) d.chi2 = chi2;  // the least (NaN at first)
      if (chi2 <= params_.gate_chi2) agreeing.emplace_back(chi2, i);
    }
  }
  // c waits, `found` waiting ones agreeing with it and among themselves.
  const auto wait = [&](std::size_t found) {
    waiting_.push_back({c, attempt});
    d.reason = formatted("waits for %zu more agreeing relocalisation(s) between these pieces", needed - 1 - found);
    if (std::isfinite(d.chi2) && agreeing.empty())
      d.reason += formatted(" (disagrees with the waiting ones: least chi-square %.1f > %.2f)", d.chi2, params_.gate_chi2);
    else if (found < agreeing.size())
      d.reason += " (the waiting ones that agree with it disagree among themselves)";
    return d;
  };
  // The votes that join must agree among themselves too, not only with c: the largest set of
  // waiting ones that agree with c and pairwise with each other (a maximum clique of the
  // agreement graph), over the best kMaxCandidates of them by their chi-square against c.
  std::sort(agreeing.begin(), agreeing.end());
  if (agreeing.size() > kMaxCandidates) agreeing.resize(kMaxCandidates);
  if (agreeing.size() + 1 < needed) return wait(agreeing.size());  // no set could join: nothing to search
  const std::size_t n = agreeing.size();
  std::vector<char> agree(n * n, 0);  // agree[i n + j]: candidates i and j agree
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) {
      const PoseConstraint &a = waiting_[agreeing[i].second].constraint, &b = waiting_[agreeing[j].second].constraint;
      double chi2 = chi2Of(a, b, covarianceOf(b));
      if (std::isnan(chi2)) chi2 = chi2Of(b, a, covarianceOf(a));  // the other way round
      agree[i * n + j] = agree[j * n + i] = chi2 <= params_.gate_chi2;  // false for NaN (neither predicts the other)
    }
  std::vector<std::size_t> chosen;  // positions in waiting_
  for (const std::size_t k : largestAgreeingSet(agree, n)) chosen.push_back(agreeing[k].second);
  if (chosen.size() + 1 < needed) return wait(chosen.size());
  d.join = true;
  std::sort(chosen.begin(), chosen.end());
  for (std::size_t k = chosen.size(); k-- > 0;) {  // from the back, so positions stay valid
    d.votes.insert(d.votes.begin(), waiting_[chosen[k]]);
    waiting_.erase(waiting_.begin() + static_cast<std::ptrdiff_t>(chosen[k]));
  }
  d.votes.push_back({c, attempt});
  return d;
}

std::vector<RelocalisationVotes::Vote> RelocalisationVotes::removeJoined(const std::vector<std::size_t>& roots) {
  std::vector<Vote> removed, kept;
  for (Vote& v : waiting_) {
    const bool joined = v.constraint.from < roots.size() && v.constraint.to < roots.size() &&
                        roots[v.constraint.from] == roots[v.constraint.to];
    (joined ? removed : kept).push_back(std::move(v));
  }
  waiting_.swap(kept);
  return removed;
}

}  // namespace gasp
