#include "pairs_table.h"

#include <cmath>
#include <cstdio>
#include <utility>

#include "gasp/eval/error_statistics.h"

namespace gasp::pairs {

double median(std::vector<double> v) { return eval::computeStatistics(std::move(v)).median; }

std::vector<eval::SkipSummary> printPairsTable(const std::vector<std::size_t>& skips,
                                               const std::vector<std::string>& methods, const PairsTally& tally,
                                               std::size_t& total_pairs) {
  std::vector<eval::SkipSummary> rows;
  total_pairs = 0;
  std::printf("%-6s %-14s %6s %6s %10s %11s %8s %13s %10s\n", "skip", "method", "pairs", "failed", "rmse_t_m",
              "rmse_r_deg", "fail_%", "within5cm2deg%", "median_ms");
  static const std::vector<eval::PairOutcome> kNone;
  for (const std::size_t skip : skips)
    for (const auto& method : methods) {
      const auto bm = tally.by_method.find(method);
      const auto s = eval::summarise(bm == tally.by_method.end() ? kNone : bm->second, skip, method);
      total_pairs += s.pairs;
      const auto na = tally.no_rgb.find({skip, method});
      if (s.pairs == 0 && na != tally.no_rgb.end()) {
        std::printf("%-6zu %-14s n/a (no rgb: %zu pairs left out)\n", skip, method.c_str(), na->second);
        continue;
      }
      if (s.pairs == 0) {  // no start frame with ground truth for this skip: nothing scored
        std::printf("%-6zu %-14s %6zu  no pair with ground truth for both frames\n", skip, method.c_str(), s.pairs);
        continue;
      }
      rows.push_back(s);
      if (std::isfinite(s.rmse_t_m))
        std::printf("%-6zu %-14s %6zu %6zu %10.4f %11.3f %8.1f %13.1f %10.1f", s.skip, s.method.c_str(), s.pairs,
                    s.failed, s.rmse_t_m, s.rmse_r_deg, s.fail_pct, s.within_pct, s.median_ms);
      else  // every pair failed: there is no error to average
        std::printf("%-6zu %-14s %6zu %6zu %10s %11s %8.1f %13.1f %10.1f", s.skip, s.method.c_str(), s.pairs, s.failed,
                    "n/a", "n/a", s.fail_pct, s.within_pct, s.median_ms);
      if (na != tally.no_rgb.end()) {
        const auto ps = tally.pairs_per_skip.find(skip);
        std::printf("  (%zu of %zu pairs without rgb left out)", na->second,
                    ps == tally.pairs_per_skip.end() ? std::size_t{0} : ps->second);
      }
      std::printf("\n");
    }
  return rows;
}

void printStageTimes(const std::vector<std::string>& methods, const PairsTally& tally) {
  for (const auto& method : methods) {
    const auto st = tally.stage_ms.find(method);
    if (st == tally.stage_ms.end()) continue;
    std::printf("median_ms_per_stage %s:", method.c_str());
    for (const auto& [stage, v] : st->second) std::printf(" %s %.1f", stage.c_str(), median(v));
    std::printf("\n");
  }
}

}  // namespace gasp::pairs
