#include "gasp/eval/pair_protocol.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <cstdio>

#include "gasp/core/error.h"

namespace gasp::eval {

std::vector<std::pair<std::size_t, std::size_t>> makePairs(std::size_t num_frames, std::size_t skip,
                                                           std::size_t starts_every) {
  if (skip < 1) throw Error("makePairs: skip must be >= 1");
  if (starts_every < 1) throw Error("makePairs: starts_every must be >= 1");
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  for (std::size_t i = 0; i + skip < num_frames; i += starts_every) pairs.emplace_back(i, i + skip);
  return pairs;
}

void scorePose(const Isometry3& T_est, const Isometry3& T_gt, PairOutcome& outcome) {
  const Isometry3 E = T_gt.inverse() * T_est;
  outcome.t_err_m = translationNorm(E);
  outcome.r_err_deg = rotationAngle(E) * 180.0 / M_PI;
}

SkipSummary summarise(const std::vector<PairOutcome>& outcomes, std::size_t skip, const std::string& method) {
  SkipSummary s;
  s.skip = skip;
  s.method = method;
  double sum_t = 0, sum_r = 0;
  std::size_t estimated = 0, within = 0;
  std::vector<double> ms;
  for (const auto& o : outcomes) {
    if (o.skip != skip) continue;
    ++s.pairs;
    ms.push_back(o.ms);
    if (!o.estimated) {
      ++s.failed;
      continue;
    }
    ++estimated;
    sum_t += o.t_err_m * o.t_err_m;
    sum_r += o.r_err_deg * o.r_err_deg;
    within += o.t_err_m <= kWithinTranslationM && o.r_err_deg <= kWithinRotationDeg;
  }
  if (estimated == 0) {  // no estimate, no error to speak of (not an error of 0)
    s.rmse_t_m = s.rmse_r_deg = std::numeric_limits<double>::quiet_NaN();
  } else {
    s.rmse_t_m = std::sqrt(sum_t / static_cast<double>(estimated));
    s.rmse_r_deg = std::sqrt(sum_r / static_cast<double>(estimated));
  }
  if (s.pairs > 0) {
    s.fail_pct = 100.0 * static_cast<double>(s.failed) / static_cast<double>(s.pairs);
    s.within_pct = 100.0 * static_cast<double>(within) / static_cast<double>(s.pairs);
    std::sort(ms.begin(), ms.end());
    const std::size_t n = ms.size();
    s.median_ms = n % 2 ? ms[n / 2] : 0.5 * (ms[n / 2 - 1] + ms[n / 2]);
  }
  return s;
}

std::string csvHeader() {
  return "skip,method,pairs,failed,rmse_t_m,rmse_r_deg,fail_pct,within_5cm_2deg_pct,median_ms";
}

std::string csvRow(const SkipSummary& s) {
  char rmse[64] = ",";  // empty cells without an estimate
  if (std::isfinite(s.rmse_t_m) && std::isfinite(s.rmse_r_deg))
    std::snprintf(rmse, sizeof rmse, "%.4f,%.3f", s.rmse_t_m, s.rmse_r_deg);
  char buf[256];
  std::snprintf(buf, sizeof buf, "%zu,%s,%zu,%zu,%s,%.1f,%.1f,%.1f", s.skip, s.method.c_str(), s.pairs, s.failed, rmse,
                s.fail_pct, s.within_pct, s.median_ms);
  return buf;
}

}  // namespace gasp::eval
