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
  // The votes that join must agree among themselves too, not only with c: the waiting ones that
  // agree with c, the best first, each kept when the ones kept before it predict it within the gate.
  std::sort(agreeing.begin(), agreeing.end());
  std::vector<std::size_t> chosen;  // positions in waiting_
  for (const auto& [chi2_c, i] : agreeing) {
    bool consistent = true;
    for (const std::size_t j : chosen) {
      const PoseConstraint &a = waiting_[j].constraint, &b = waiting_[i].constraint;
      double chi2 = chi2Of(a, b, covarianceOf(b));
      if (std::isnan(chi2)) chi2 = chi2Of(b, a, covarianceOf(a));  // the other way round
      consistent = consistent && chi2 <= params_.gate_chi2;  // false for NaN (neither predicts the other)
    }
    if (consistent) chosen.push_back(i);
  }
  if (chosen.size() + 1 >= needed) {
    d.join = true;
    std::sort(chosen.begin(), chosen.end());
    for (std::size_t k = chosen.size(); k-- > 0;) {  // from the back, so positions stay valid
      d.votes.insert(d.votes.begin(), waiting_[chosen[k]]);
      waiting_.erase(waiting_.begin() + static_cast<std::ptrdiff_t>(chosen[k]));
    }
    d.votes.push_back({c, attempt});
    return d;
  }
  waiting_.push_back({c, attempt});
  d.reason = formatted("waits for %zu more agreeing relocalisation(s) between these pieces", needed - 1 - chosen.size());
  if (std::isfinite(d.chi2) && agreeing.empty())
    d.reason += formatted(" (disagrees with the waiting ones: least chi-square %.1f > %.2f)", d.chi2, params_.gate_chi2);
  else if (chosen.size() < agreeing.size())
    d.reason += " (the waiting ones that agree with it disagree among themselves)";
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
