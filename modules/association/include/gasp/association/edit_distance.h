#pragma once
/// \file edit_distance.h Restricted Damerau-Levenshtein (optimal string alignment, OSA) distance
/// between two sequences under a match predicate, with early termination (paper section III-D,
/// Algorithm 1, corrected in NOTES item 4). Generic: works on feature sets (with FeatureMatch)
/// and on strings (with ==).
///
/// Recurrence (1-based, a = Q, b = Q', M(i, j) = match(a_i, b_j)):
///   tab[i][0] = i * del,  tab[0][j] = j * ins
///   tab[i][j] = min( tab[i-1][j]   + del,
///                    tab[i][j-1]   + ins,
///                    tab[i-1][j-1] + (M(i, j) ? 0 : replace) )        (erratum: listing has tab[i][j-1])
///   if i, j > 1 and M(i, j-1) and M(i-1, j):                           (erratum: OSA condition)
///     tab[i][j] = min(tab[i][j], tab[i-2][j-2] + transpose)
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "gasp/core/error.h"

namespace gasp {

/// Operation costs. Defaults are the paper's: insert = delete = 1, replace disabled (infinity:
/// replacing a patch by another is physically meaningless), transposition of adjacent elements 0
/// (absorbs order flips from the tolerant ordering). Unit costs with replace = 1 give the textbook
/// OSA distance.
struct EditCosts {
  double insert = 1.0;  ///< one element of the second sequence unmatched (> 0, finite)
  double del = 1.0;     ///< one element of the first sequence unmatched (> 0, finite)
  double replace = std::numeric_limits<double>::infinity();  ///< mismatched pair aligned (>= 0, may be inf)
  double transpose = 0.0;  ///< two adjacent elements matched crosswise (>= 0, may be inf)
};

/// Throws gasp::Error unless insert, del are finite and > 0 and replace, transpose are >= 0.
inline void validate(const EditCosts& c) {
  if (!(c.insert > 0.0) || !std::isfinite(c.insert) || !(c.del > 0.0) || !std::isfinite(c.del)) {
    throw Error("EditCosts: insert and delete costs must be finite and > 0, got " +
                std::to_string(c.insert) + " and " + std::to_string(c.del));
  }
  if (!(c.replace >= 0.0) || !(c.transpose >= 0.0)) {
    throw Error("EditCosts: replace and transpose costs must be >= 0 (infinity disables), got " +
                std::to_string(c.replace) + " and " + std::to_string(c.transpose));
  }
}

/// Returned by osaDistance() when the distance exceeds the bound.
inline constexpr double kExceedsBound = std::numeric_limits<double>::infinity();

/// Scratch memory of osaDistance(): three rolling DP rows and two rolling rows of match results.
/// Reuse one per thread to avoid allocation per call (capacity only grows).
struct EditDistanceWorkspace {
  std::vector<double> rows;
  std::vector<unsigned char> matches;
};

/// OSA distance between a and b (any sequences with size() and operator[]) where
/// match(a[i], b[j]) says whether two elements are the same. Each pair is tested at most once
/// (its result is kept for the transposition test of the next cell and the next row).
///
/// Early termination: returns kExceedsBound (+inf) when the distance exceeds `bound`, and
/// otherwise exactly the distance. The DP stops as soon as two consecutive rows contain no cell
/// whose value plus the insert/delete cost still needed to reach the last cell (the change of
/// i - j) is <= bound: every alignment path visits one of any two consecutive rows (a
/// transposition skips one row), costs are non-negative, and only insertions/deletions change
/// i - j, so the distance then exceeds the bound. O(|a| |b|) time, O(|b|) memory.
template <class SeqA, class SeqB, class MatchFn>
double osaDistance(const SeqA& a, const SeqB& b, MatchFn&& match, const EditCosts& costs,
                   double bound, EditDistanceWorkspace& ws) {
  validate(costs);
  if (std::isnan(bound)) throw Error("osaDistance: bound is NaN");
  const std::size_t n = a.size();
  const std::size_t m = b.size();
  const double ins = costs.insert, del = costs.del, rep = costs.replace, tr = costs.transpose;
  const double nm_diff = static_cast<double>(n) - static_cast<double>(m);
  // Lower bound of the cost still needed from cell (i, j) to (n, m): the diagonal offset i - j
  // must change by delta = (n - m) - (i - j), +1 per deletion, -1 per insertion.
  const auto remaining = [&](double delta) { return std::max(delta * del, -delta * ins); };

  if (n == 0 || m == 0) {
    const double d = static_cast<double>(n) * del + static_cast<double>(m) * ins;
    return d <= bound ? d : kExceedsBound;
  }

  // Rows are padded by one sentinel cell (+inf) in front so that tab[i-2][j-2] at j = 1 needs no
  // branch: R[-1] is valid.
  constexpr double inf = std::numeric_limits<double>::infinity();
  const std::size_t w = m + 2;
  if (ws.rows.size() < 3 * w) ws.rows.resize(3 * w);
  if (ws.matches.size() < 2 * (m + 1)) ws.matches.resize(2 * (m + 1));
  double* r2 = ws.rows.data() + 1;          // row i-2
  double* r1 = ws.rows.data() + w + 1;      // row i-1
  double* r0 = ws.rows.data() + 2 * w + 1;  // row i
  unsigned char* mp = ws.matches.data();          // M(i-1, j)
  unsigned char* mc = ws.matches.data() + m + 1;  // M(i, j)
  std::fill(ws.rows.begin(), ws.rows.begin() + static_cast<std::ptrdiff_t>(3 * w), inf);
  std::fill(ws.matches.begin(), ws.matches.begin() + static_cast<std::ptrdiff_t>(2 * (m + 1)), 0);

  // Lowest "cell + remaining" of the previous row (row 0 here).
  double prev_min = inf;
  for (std::size_t j = 0; j <= m; ++j) {
    r1[j] = static_cast<double>(j) * ins;
    prev_min = std::min(prev_min, r1[j] + remaining(nm_diff + static_cast<double>(j)));
  }

  for (std::size_t i = 1; i <= n; ++i) {
    const auto& ai = a[i - 1];
    r0[0] = static_cast<double>(i) * del;
    // delta(i, j) = (n - m) - (i - j) = base + j
    const double base = nm_diff - static_cast<double>(i);
    double row_min = r0[0] + remaining(base);
    // Branch-free inner loop (which pairs match is unpredictable). The only loop-carried
    // dependency is the insertion term: it is kept in a register and applied last, so the chain
    // per cell is one add and one min.
    double left = r0[0];
    for (std::size_t j = 1; j <= m; ++j) {
      const bool mij = static_cast<bool>(match(ai, b[j - 1]));
      mc[j] = static_cast<unsigned char>(mij);
      const double up = r1[j] + del;
      const double diag = r1[j - 1] + (mij ? 0.0 : rep);
      const double swap = (mc[j - 1] & mp[j]) ? r2[static_cast<std::ptrdiff_t>(j) - 2] + tr : inf;
      const double d = std::min(std::min(up, std::min(diag, swap)), left + ins);
      r0[j] = d;
      left = d;
      const double delta = base + static_cast<double>(j);
      row_min = std::min(row_min, d + std::max(delta * del, -delta * ins));
    }
    if (row_min > bound && prev_min > bound) return kExceedsBound;
    prev_min = row_min;
    // Roll: row i becomes i-1, i-1 becomes i-2.
    double* tmp = r2;
    r2 = r1;
    r1 = r0;
    r0 = tmp;
    std::swap(mp, mc);
  }
  const double d = r1[m];
  return d <= bound ? d : kExceedsBound;
}

/// osaDistance() with a per-thread workspace.
template <class SeqA, class SeqB, class MatchFn>
double osaDistance(const SeqA& a, const SeqB& b, MatchFn&& match, const EditCosts& costs = {},
                   double bound = std::numeric_limits<double>::infinity()) {
  thread_local EditDistanceWorkspace ws;
  return osaDistance(a, b, std::forward<MatchFn>(match), costs, bound, ws);
}

/// Normalised distance D_hat = D / (k_S + k_S') (paper section III-E, NOTES item 5): in [0, 1]
/// with unit insert/delete costs and replace disabled. Two empty sets give +inf (no evidence:
/// never accepted).
inline double normalisedDistance(double distance, std::size_t k_s, std::size_t k_s_prime) {
  const std::size_t total = k_s + k_s_prime;
  if (total == 0) return std::numeric_limits<double>::infinity();
  return distance / static_cast<double>(total);
}

/// The early-termination bound B = lambda (k_S + k_S') for gating threshold lambda in [0, 1]
/// (paper section III-E): D_hat <= lambda iff D <= B. Throws gasp::Error for lambda outside [0, 1].
inline double distanceBound(double lambda, std::size_t k_s, std::size_t k_s_prime) {
  if (!(lambda >= 0.0 && lambda <= 1.0)) {
    throw Error("distanceBound: lambda must be in [0, 1], got " + std::to_string(lambda));
  }
  return lambda * static_cast<double>(k_s + k_s_prime);
}

}  // namespace gasp
