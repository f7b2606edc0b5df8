#include "gasp/association/banded_distance.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <iterator>
#include <limits>

#if defined(__SSE2__) || defined(_M_X64)
#include <emmintrin.h>
#define GASP_BANDED_SSE2 1
#endif

#include "gasp/core/error.h"

namespace gasp {
namespace {

constexpr double kNegInf = -std::numeric_limits<double>::infinity();

/// Scaled values above this magnitude are not float-safe: with |s| <= 1024 the float copy and the
/// float difference are within 2.5e-4 of the exact scaled difference, well inside kFloatMargin.
constexpr double kFloatSafeLimit = 1024.0;
/// Float test decides only when |d| <= 1 - margin (match) or some |d| > 1 + margin (no match).
constexpr float kFloatMargin = 1e-3f;

/// Components whose matching bound is tried before the DP, most selective first (measured on
/// TUM pairs: 0 and 2 each reject about a third of the candidates the DP would reject).
constexpr int kBoundComponents[] = {0, 2, 4};

/// Largest key0 span with a lookup table (bins of e_r: 4096 x 2 cm = 82 m).
constexpr std::size_t kMaxKeyTable = 4096;

/// Runs of equal component-0 key at least this long are cut down by the component-1 key (shorter
/// ones cost less to test than to search).
constexpr std::size_t kSplitRun = 8;

/// Match(a_i, b_j) on the doubles (FeatureMatch, the definition).
inline bool exactMatch(const Feature& x, const Feature& y, double r, double t) {
  return (std::abs(x[0] - y[0]) <= r) & (std::abs(x[1] - y[1]) <= r) & (std::abs(x[2] - y[2]) <= r) &
         (std::abs(x[3] - y[3]) <= r) & (std::abs(x[4] - y[4]) <= t) & (std::abs(x[5] - y[5]) <= t) &
         (std::abs(x[6] - y[6]) <= t);
}

/// Whether the maximum matching of sorted x and y under fl(|x - y|) <= tol reaches `target`.
/// Greedy two-pointer walk: it is exact for this one-dimensional compatibility (an unmatched
/// smallest element that is incompatible with the other list's smallest cannot match anything
/// later; a compatible pair of smallest elements can be exchanged into any optimal matching).
/// Stops as soon as the answer is known.
bool matchingReaches(const double* x, std::size_t n, const double* y, std::size_t m, double tol,
                     std::size_t target) {
  std::size_t i = 0, j = 0, mm = 0;
  if (std::min(n, m) < target) return false;
  while (i < n && j < m) {
    const double d = x[i] - y[j];
    const bool match = std::abs(d) <= tol;
    const bool x_smaller = d < 0.0;
    mm += match;
    i += match | x_smaller;
    j += match | !x_smaller;
    if (mm >= target) return true;
    if (mm + std::min(n - i, m - j) < target) return false;
  }
  return mm >= target;
}

}  // namespace

PreparedFeatureSet prepareFeatureSet(const std::vector<Feature>& q, const MatchParams& match,
                                     const OrderingParams& ordering) {
  validate(match);
  validate(ordering);
  PreparedFeatureSet p;
  p.features = q;
  const std::size_t n = q.size();
  for (auto* v : {&p.key0, &p.key0_lo, &p.key0_hi, &p.key1, &p.key1_lo, &p.key1_hi}) v->resize(n);
  p.run_end.resize(n);
  p.scaled.assign(8 * n, 0.0f);
  p.key0_sorted = true;
  p.key01_sorted = true;
  p.float_safe = match.r_dev_m > 0.0 && match.theta_dev_rad > 0.0;
  bool finite = true;
  const double r = match.r_dev_m;
  // Any y with fl(|x - y|) <= r lies in [x - r - delta, x + r + delta] even after rounding; the
  // key is non-decreasing in the value, so its key lies in [key_lo, key_hi]. NaN or infinite x
  // matches nothing (|x - y| is NaN or infinite): empty range.
  const auto keyRange = [&](double x, std::int64_t& lo, std::int64_t& hi) {
    if (std::isfinite(x)) {
      const double delta = 1e-9 * (std::abs(x) + r);
      lo = quantiseComponent(x - r - delta, ordering.e_r_m);
      hi = quantiseComponent(x + r + delta, ordering.e_r_m);
    } else {
      lo = 1;
      hi = 0;
    }
  };
  for (std::size_t i = 0; i < n; ++i) {
    p.key0[i] = quantiseComponent(q[i][0], ordering.e_r_m);
    p.key1[i] = quantiseComponent(q[i][1], ordering.e_r_m);
    if (i > 0 && p.key0[i] < p.key0[i - 1]) p.key0_sorted = false;
    if (i > 0 && std::make_pair(p.key0[i], p.key1[i]) < std::make_pair(p.key0[i - 1], p.key1[i - 1]))
      p.key01_sorted = false;
    keyRange(q[i][0], p.key0_lo[i], p.key0_hi[i]);
    keyRange(q[i][1], p.key1_lo[i], p.key1_hi[i]);
    for (std::size_t c = 0; c < 7; ++c) finite = finite && std::isfinite(q[i][c]);
    if (p.float_safe) {
      for (std::size_t c = 0; c < 7; ++c) {
        const double s = q[i][c] / (c < kFeatureDistanceComponents ? match.r_dev_m : match.theta_dev_rad);
        if (!(std::abs(s) <= kFloatSafeLimit)) {
          p.float_safe = false;
          break;
        }
        p.scaled[8 * i + c] = static_cast<float>(s);
      }
    }
  }
  if (!p.float_safe) p.scaled.clear();
  for (std::size_t i = n; i-- > 0;) {
    p.run_end[i] = (i + 1 < n && p.key0[i + 1] == p.key0[i]) ? p.run_end[i + 1] : static_cast<std::uint32_t>(i + 1);
  }
  if (p.key0_sorted && n > 0) {
    const std::int64_t lo = p.key0.front(), hi = p.key0.back();
    // hi - lo < 2^62 always (saturated keys); the table is kept small.
    if (hi - lo <= static_cast<std::int64_t>(kMaxKeyTable)) {
      p.key0_min = lo;
      p.key0_first.resize(static_cast<std::size_t>(hi - lo) + 2);
      std::size_t i = 0;
      for (std::size_t k = 0; k < p.key0_first.size(); ++k) {
        while (i < n && p.key0[i] < lo + static_cast<std::int64_t>(k)) ++i;
        p.key0_first[k] = static_cast<std::uint32_t>(i);
      }
    }
  }
  if (finite) {
    p.sorted_values.resize(7 * n);
    for (std::size_t k = 0; k < 7; ++k) {
      double* v = p.sorted_values.data() + k * n;
      for (std::size_t i = 0; i < n; ++i) v[i] = q[i][k];
      std::sort(v, v + n);
    }
  }
  return p;
}

namespace {

/// Windows of `cols` for the rows of `rows`: [lo, hi) per row (run borders of key0), and the number
/// of rows from i on with a non-empty window. Full windows when the keys are not sorted.
void computeWindows(const PreparedFeatureSet& rows, const PreparedFeatureSet& cols, BandedWorkspace& ws) {
  const std::size_t n = rows.size(), m = cols.size();
  ws.lo.resize(n);
  ws.hi.resize(n);
  ws.usable_after.resize(n + 1);
  const bool band = rows.key0_sorted && cols.key0_sorted;
  if (band && !cols.key0_first.empty()) {
    // Table lookups: first index with key >= klo, first index with key > khi.
    const std::int64_t kmin = cols.key0_min;
    const auto span = static_cast<std::int64_t>(cols.key0_first.size()) - 1;  // keys kmin .. kmin + span - 1
    const std::uint32_t* first = cols.key0_first.data();
    const auto at = [&](std::int64_t k) -> std::uint32_t {
      const std::int64_t d = k - kmin;
      return d <= 0 ? 0u : (d >= span ? static_cast<std::uint32_t>(m) : first[d]);
    };
    std::uint32_t usable = 0;
    for (std::size_t i = n; i-- > 0;) {
      const std::int64_t klo = rows.key0_lo[i], khi = rows.key0_hi[i];
      const std::uint32_t lo = at(klo);
      const std::uint32_t hi = klo > khi ? lo : at(khi + 1);
      ws.lo[i] = lo;
      ws.hi[i] = hi;
      ws.usable_after[i + 1] = usable;
      usable += hi > lo;
    }
    ws.usable_after[0] = usable;
    return;
  }
  const std::int64_t* kb = cols.key0.data();
  std::size_t lo = 0, hi = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const std::int64_t klo = rows.key0_lo[i], khi = rows.key0_hi[i];
    if (klo > khi) {
      ws.lo[i] = ws.hi[i] = 0;
      continue;
    }
    if (!band) {
      ws.lo[i] = 0;
      ws.hi[i] = static_cast<std::uint32_t>(m);
      continue;
    }
    while (lo < m && kb[lo] < klo) ++lo;
    while (lo > 0 && kb[lo - 1] >= klo) --lo;
    while (hi < m && kb[hi] <= khi) ++hi;
    while (hi > 0 && kb[hi - 1] > khi) --hi;
    ws.lo[i] = static_cast<std::uint32_t>(lo);
    ws.hi[i] = static_cast<std::uint32_t>(std::max(lo, hi));
  }
  ws.usable_after[n] = 0;
  for (std::size_t i = n; i-- > 0;) ws.usable_after[i] = ws.usable_after[i + 1] + (ws.hi[i] > ws.lo[i]);
}

/// The match test of one row against the columns that can match it.
class RowMatcher {
 public:
  RowMatcher(const PreparedFeatureSet& rows, const PreparedFeatureSet& cols, const MatchParams& mp)
      : rows_(rows), cols_(cols), rd_(mp.r_dev_m), td_(mp.theta_dev_rad),
        use_float_(rows.float_safe && cols.float_safe),
        split_(rows.key0_sorted && cols.key0_sorted && rows.key01_sorted && cols.key01_sorted) {}

  /// Sub-runs of row r's window [lo, hi) (lo and hi are borders of key0 runs): each key0 run, cut
  /// to its elements with key1 in the row's key1 range when it is long (sorted by key1 inside).
  /// visit(begin, end) for each non-empty one, in increasing order.
  template <class Visit>
  void forSubRuns(std::size_t r, std::size_t lo, std::size_t hi, Visit&& visit) const {
    const std::int64_t* kb1 = cols_.key1.data();
    for (std::size_t j = lo; j < hi;) {
      const std::size_t e = cols_.run_end[j];
      std::size_t s0 = j, e0 = e;
      if (split_ && e - j >= kSplitRun) {
        s0 = static_cast<std::size_t>(std::lower_bound(kb1 + j, kb1 + e, rows_.key1_lo[r]) - kb1);
        e0 = static_cast<std::size_t>(std::upper_bound(kb1 + s0, kb1 + e, rows_.key1_hi[r]) - kb1);
      }
      if (s0 < e0) visit(s0, e0);
      j = e;
    }
  }

  /// The same as begin, end pairs, adjacent sub-runs merged.
  void subRuns(std::size_t r, std::size_t lo, std::size_t hi, std::vector<std::uint32_t>& runs) const {
    runs.clear();
    forSubRuns(r, lo, hi, [&runs](std::size_t s0, std::size_t e0) {
      if (!runs.empty() && runs.back() == s0) {
        runs.back() = static_cast<std::uint32_t>(e0);
      } else {
        runs.push_back(static_cast<std::uint32_t>(s0));
        runs.push_back(static_cast<std::uint32_t>(e0));
      }
    });
  }

  /// Match(row r, column c) for c in [begin, end): sink(c, bool) for each.
  template <class Sink>
  void test(std::size_t r, std::size_t begin, std::size_t end, Sink&& sink) const {
    const Feature& x = rows_.features[r];
    if (!use_float_) {
      for (std::size_t c = begin; c < end; ++c) sink(c, exactMatch(x, cols_.features[c], rd_, td_));
      return;
    }
    const float* xa = rows_.scaled.data() + 8 * r;
#ifdef GASP_BANDED_SSE2
    const __m128 abs_mask = _mm_castsi128_ps(_mm_set1_epi32(0x7fffffff));
    const __m128 in_limit = _mm_set1_ps(1.0f - kFloatMargin);
    const __m128 out_limit = _mm_set1_ps(1.0f + kFloatMargin);
    const __m128 x0 = _mm_loadu_ps(xa), x1 = _mm_loadu_ps(xa + 4);
    for (std::size_t c = begin; c < end; ++c) {
      // Distances first (most pairs fail there), then the angles.
      const float* yb = cols_.scaled.data() + 8 * c;
      const __m128 d0 = _mm_and_ps(_mm_sub_ps(x0, _mm_loadu_ps(yb)), abs_mask);
      if (_mm_movemask_ps(_mm_cmpgt_ps(d0, out_limit))) {
        sink(c, false);
        continue;
      }
      const __m128 d1 = _mm_and_ps(_mm_sub_ps(x1, _mm_loadu_ps(yb + 4)), abs_mask);
      bool f;
      if (_mm_movemask_ps(_mm_cmpgt_ps(d1, out_limit))) {
        f = false;
      } else if (_mm_movemask_ps(_mm_and_ps(_mm_cmple_ps(d0, in_limit), _mm_cmple_ps(d1, in_limit))) == 0xF) {
        f = true;
      } else {
        f = exactMatch(x, cols_.features[c], rd_, td_);
      }
      sink(c, f);
    }
#else
    for (std::size_t c = begin; c < end; ++c) {
      const float* yb = cols_.scaled.data() + 8 * c;
      bool out = false, in = true;
      for (int k = 0; k < 7; ++k) {
        const float d = std::abs(xa[k] - yb[k]);
        out |= d > 1.0f + kFloatMargin;
        in &= d <= 1.0f - kFloatMargin;
      }
      sink(c, out ? false : (in ? true : exactMatch(x, cols_.features[c], rd_, td_)));
    }
#endif
  }

 private:
  const PreparedFeatureSet& rows_;
  const PreparedFeatureSet& cols_;
  double rd_, td_;
  bool use_float_, split_;
};

inline std::uint64_t lowMask(std::size_t bits) { return bits >= 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << bits) - 1; }

inline std::size_t lowestBit(std::uint64_t x) {
#if defined(__GNUC__) || defined(__clang__)
  return static_cast<std::size_t>(__builtin_ctzll(x));
#else
  std::size_t p = 0;
  while (!(x & 1)) {
    x >>= 1;
    ++p;
  }
  return p;
#endif
}

/// Bit count without a library call (the build targets baseline x86-64, without POPCNT).
inline int popcount64(std::uint64_t x) {
  x = x - ((x >> 1) & 0x5555555555555555ULL);
  x = (x & 0x3333333333333333ULL) + ((x >> 2) & 0x3333333333333333ULL);
  x = (x + (x >> 4)) & 0x0F0F0F0F0F0F0F0FULL;
  return static_cast<int>((x * 0x0101010101010101ULL) >> 56);
}

/// Transposition cost 0 (paper), at most 64 columns: the gain is g L with L the number of matched
/// elements (a transposition matches two), computed bit-parallel. Row i is the bit vector I_i of
/// the columns where L[i][.] increases (L[i][j] = popcount(I_i & lowMask(j)); steps are 0 or 1).
/// Matches: the LCS step of Hyyrö (2004) on V = ~I: U = V & M, V' = (V + U) | (V - U).
/// Transpositions at column j (M(i, j-1) and M(i-1, j)) give L[i-2][j-2] + 2, at most one more
/// than the LCS step there; when it is more, the increase moves from the next increase column
/// after j to j (processed left to right). Returns L, or -1 when the early termination fires
/// (`target` pairs cannot be reached).
long bitParallelPairs(const PreparedFeatureSet& rows, const PreparedFeatureSet& cols, const MatchParams& mp,
                      std::size_t target, BandedWorkspace& ws) {
  const std::size_t n = rows.size(), m = cols.size();
  computeWindows(rows, cols, ws);
  const RowMatcher matcher(rows, cols, mp);
  const std::uint64_t all = lowMask(m);
  std::uint64_t inc1 = 0, inc2 = 0;  // I of rows i-1 and i-2
  std::uint64_t m_prev = 0;          // match mask of row i-1
  bool prev_short = std::min(n, m) < target;
  for (std::size_t i = 1; i <= n; ++i) {
    std::uint64_t mask = 0;
    const std::size_t lo = ws.lo[i - 1], hi = ws.hi[i - 1];
    if (lo < hi) {
      matcher.forSubRuns(i - 1, lo, hi, [&](std::size_t s0, std::size_t e0) {
        matcher.test(i - 1, s0, e0, [&mask](std::size_t c, bool f) { mask |= static_cast<std::uint64_t>(f) << c; });
      });
    }
    std::uint64_t inc = inc1;
    if (mask) {
      const std::uint64_t v = ~inc1 & all;
      const std::uint64_t u = v & mask;
      inc = ~((v + u) | (v - u)) & all;
      for (std::uint64_t s = (mask << 1) & m_prev & all; s; s &= s - 1) {
        const std::size_t p = lowestBit(s);  // column j = p + 1
        const int cur = popcount64(inc & lowMask(p + 1));
        const int cand = (p >= 1 ? popcount64(inc2 & lowMask(p - 1)) : 0) + 2;
        if (cand > cur) {
          const std::uint64_t above = inc & ~lowMask(p + 1);
          inc |= std::uint64_t{1} << p;
          if (above) inc &= ~(above & (~above + 1));
        }
      }
    }
    inc2 = inc1;
    inc1 = inc;
    m_prev = mask;
    // Early termination (as in the sparse DP): L <= L[i][m - c] + c, c = rows left that can match.
    const std::size_t cap = std::min<std::size_t>(ws.usable_after[i], m);
    const bool short_now = static_cast<std::size_t>(popcount64(inc & lowMask(m - cap))) + cap < target;
    if (short_now && prev_short) return -1;
    prev_short = short_now;
  }
  return popcount64(inc1);
}

/// General costs (transposition > 0, or more than 64 columns both ways): the sparse DP on G. Row i
/// is row i-1 raised at its matches (G[i-1][j-1] + g at column j) and transpositions (M(i, j-1)
/// and M(i-1, j): G[i-2][j-2] + g2 at column j), then kept non-decreasing.
double sparseDistance(const PreparedFeatureSet& a, const PreparedFeatureSet& b, const MatchParams& mp,
                      const EditCosts& costs, double bound, double cut_below, BandedWorkspace& ws) {
  const std::size_t n = a.size(), m = b.size();
  const double ins = costs.insert, del = costs.del, tr = costs.transpose;
  const double g = ins + del;
  const bool swaps = tr < 2.0 * g;
  const double g2 = 2.0 * g - tr;  // gain of a transposition (two pairs matched crosswise)
  const double total = static_cast<double>(n) * del + static_cast<double>(m) * ins;
  computeWindows(a, b, ws);
  const RowMatcher matcher(a, b, mp);

  // Three rows of G (row 0 = 0) and two rows of match flags (1-based columns, index 0 and m + 1
  // always 0), zero outside the sub-runs.
  const std::size_t w = m + 1;
  if (ws.gain.size() < 3 * w) ws.gain.resize(3 * w);
  std::fill(ws.gain.begin(), ws.gain.begin() + static_cast<std::ptrdiff_t>(w), 0.0);
  if (ws.matches.size() < 2 * (m + 2)) ws.matches.resize(2 * (m + 2));
  std::fill(ws.matches.begin(), ws.matches.begin() + static_cast<std::ptrdiff_t>(2 * (m + 2)), 0);
  double* const buf[3] = {ws.gain.data(), ws.gain.data() + w, ws.gain.data() + 2 * w};
  double* r1 = buf[0];  // G[i-1]
  double* r2 = buf[0];  // G[i-2] (may alias G[i-1] when the rows are equal)
  unsigned char* mprev = ws.matches.data();         // M(i-1, j)
  unsigned char* mcur = ws.matches.data() + m + 2;  // M(i, j)
  ws.runs.clear();
  ws.prev_runs.clear();
  double prev_ub = g * static_cast<double>(std::min(n, m));

  for (std::size_t i = 1; i <= n; ++i) {
    auto& runs = ws.runs;
    runs.clear();
    if (ws.lo[i - 1] < ws.hi[i - 1]) matcher.subRuns(i - 1, ws.lo[i - 1], ws.hi[i - 1], runs);
    bool any = false;
    for (std::size_t k = 0; k < runs.size(); k += 2) {
      matcher.test(i - 1, runs[k], runs[k + 1], [&](std::size_t c, bool f) {
        mcur[c + 1] = static_cast<unsigned char>(f);
        any |= f;
      });
    }

    if (any) {
      // G[i][j] = max(G[i-1][j], best candidate in columns <= j). The candidates of sub-run
      // [s, e) lie in columns s + 1 .. e + 1; before the first the row is unchanged, elsewhere
      // it is max(G[i-1][j], running best).
      double* dst = buf[0];
      for (double* bb : buf) {
        if (bb != r1 && bb != r2) {
          dst = bb;
          break;
        }
      }
      std::size_t j = runs[0] + 1;
      std::memcpy(dst, r1, j * sizeof(double));
      double run = kNegInf;
      for (std::size_t k = 0; k < runs.size(); k += 2) {
        for (const std::size_t s0 = runs[k]; j <= s0; ++j) dst[j] = std::max(r1[j], run);
        for (const std::size_t last = std::min<std::size_t>(runs[k + 1] + 1, m); j <= last; ++j) {
          double cand = mcur[j] ? r1[j - 1] + g : kNegInf;
          if (swaps && mcur[j - 1] && mprev[j]) cand = std::max(cand, r2[j - 2] + g2);
          run = std::max(run, cand);
          dst[j] = std::max(r1[j], run);
        }
      }
      for (; j <= m && r1[j] < run; ++j) dst[j] = run;
      if (j <= m) std::memcpy(dst + j, r1 + j, (m + 1 - j) * sizeof(double));
      r2 = r1;
      r1 = dst;
    } else {
      r2 = r1;  // G[i] = G[i-1]
    }
    // Row i-1's flags are no longer needed: clear them, then roll.
    for (std::size_t k = 0; k < ws.prev_runs.size(); k += 2)
      std::fill(mprev + ws.prev_runs[k] + 1, mprev + ws.prev_runs[k + 1] + 1, 0);
    std::swap(mprev, mcur);
    std::swap(ws.prev_runs, ws.runs);

    // Early termination: any alignment path visits row i or row i-1 (a transposition skips one
    // row). Through cell (i, j) it gains at most G[i][j] + g min(c, m - j) with c the rows left
    // that can match. G[i][j] grows by at most g per column (a column holds at most one pair;
    // dropping it loses at most g since g2 <= 2g), so the maximum over j is at j = m - c.
    const std::size_t cap = std::min<std::size_t>(ws.usable_after[i], m);
    const double ub = r1[m - cap] + g * static_cast<double>(cap);
    if (ub < cut_below && prev_ub < cut_below) return kExceedsBound;
    prev_ub = ub;
  }
  const double d = total - r1[m];
  return d <= bound ? d : kExceedsBound;
}

}  // namespace

double featureSetDistance(const PreparedFeatureSet& a, const PreparedFeatureSet& b, const MatchParams& mp,
                          const EditCosts& costs, double bound, BandedWorkspace& ws) {
  validate(costs);
  if (std::isnan(bound)) throw Error("featureSetDistance: bound is NaN");
  const double ins = costs.insert, del = costs.del, tr = costs.transpose;
  const double g = ins + del;  // gain of one matched pair
  if (!(costs.replace >= g)) {
    // A replacement can beat a deletion plus an insertion: the sparse form does not hold.
    return osaDistance(a.features, b.features, FeatureMatch{mp}, costs, bound, ws.fallback);
  }
  const std::size_t n = a.size(), m = b.size();
  const double total = static_cast<double>(n) * del + static_cast<double>(m) * ins;
  if (n == 0 || m == 0) return total <= bound ? total : kExceedsBound;
  // D = total - G <= bound  <=>  G >= needed. The cuts keep a rounding slack so that they never
  // drop a result that the final test would accept.
  const double needed = total - bound;
  const double cut_below = needed - 1e-9 * total;
  // The least number of matched pairs that can reach cut_below (G <= g #pairs as g2 <= 2 g).
  const double pairs_needed = cut_below > 0.0 ? std::ceil(cut_below / g) : 0.0;
  if (pairs_needed > static_cast<double>(std::min(n, m))) {
    return kExceedsBound;
  }
  const auto target = static_cast<std::size_t>(pairs_needed);

  // Matching bounds, component by component.
  if (target > 0 && !a.sorted_values.empty() && !b.sorted_values.empty()) {
    for (const int c : kBoundComponents) {
      const auto k = static_cast<std::size_t>(c);
      if (!matchingReaches(a.sorted_values.data() + k * n, n, b.sorted_values.data() + k * m, m,
                           c < static_cast<int>(kFeatureDistanceComponents) ? mp.r_dev_m : mp.theta_dev_rad,
                           target)) {
        return kExceedsBound;
      }
    }
  }

  if (tr == 0.0 && (m <= 64 || n <= 64)) {
    // L(a, b) = L(b, a): the shorter sequence gives the columns.
    const long pairs = m <= 64 ? bitParallelPairs(a, b, mp, target, ws) : bitParallelPairs(b, a, mp, target, ws);
    if (pairs < 0) return kExceedsBound;
    const double d = total - g * static_cast<double>(pairs);
    return d <= bound ? d : kExceedsBound;
  }
  return sparseDistance(a, b, mp, costs, bound, cut_below, ws);
}

}  // namespace gasp
