#pragma once
// Internal: the free-space test's verdict from its two directions' sample counts, shared by the
// test on a view's pixels or cells (visibility_check.cpp) and on a sweep's returns
// (returns_stage.cpp), so that both apply the same limits in the same order.
#include <algorithm>
#include <cstdio>
#include <string>

#include "gasp/pipeline/visibility_check.h"

namespace gasp::detail {

/// One direction's samples: consistent, occluded (behind the other view's surface) and violating
/// (in the space the other view saw as empty).
struct FreeSpaceCounts {
  int consistent = 0, occluded = 0, violations = 0;
  double largest_blob_share = 1.0;  ///< share of the violations in the largest 8-connected blob (pixels only)
  double ratio() const {
    const int n = consistent + violations;
    return n ? static_cast<double>(violations) / n : 0.0;
  }
  double occludedRatio() const {
    const int n = consistent + occluded + violations;
    return n ? static_cast<double>(occluded) / n : 0.0;
  }
};

/// Names in the verdict's reasons: the test ("visibility check"), its samples ("samples") and the
/// other side ("view").
struct FreeSpaceWords {
  const char* test;
  const char* samples;
  const char* other;
};

/// The counts, ratios and verdict of `out` from the two directions under p's limits: too few
/// consistent samples in either direction, then the violations in the worse direction, then those
/// seen from both, then the occluded share; a refusal on the last three sets free_space_refused.
inline void decideFreeSpace(const FreeSpaceCounts& st, const FreeSpaceCounts& ts, const VisibilityCheckParams& p,
                            const FreeSpaceWords& w, VisibilityCheck& out) {
  out.consistent = st.consistent + ts.consistent;
  out.occluded = st.occluded + ts.occluded;
  out.violations = st.violations + ts.violations;
  out.violation_ratio = std::max(st.ratio(), ts.ratio());
  out.violation_ratio_lesser = std::min(st.ratio(), ts.ratio());
  out.occluded_ratio = std::max(st.occludedRatio(), ts.occludedRatio());
  out.violation_blob_share_lesser = std::min(st.largest_blob_share, ts.largest_blob_share);
  out.violation_blob_share = std::max(st.largest_blob_share, ts.largest_blob_share);
  char buf[320];
  if (std::min(st.consistent, ts.consistent) < p.min_consistent) {
    std::snprintf(buf, sizeof buf, "%s: only %d consistent %s (at least %d needed): the %ss barely overlap at this pose",
                  w.test, std::min(st.consistent, ts.consistent), w.samples, p.min_consistent, w.other);
    out.reason = buf;
    return;
  }
  if (out.violation_ratio > p.max_violation_ratio) {
    std::snprintf(buf, sizeof buf, "%s: %.0f%% of the overlapping %s lie in space the other %s saw as empty (at most %.0f%%)",
                  w.test, 100.0 * out.violation_ratio, w.samples, w.other, 100.0 * p.max_violation_ratio);
  } else if (out.violation_ratio_lesser > p.max_two_way_violation_ratio) {
    std::snprintf(buf, sizeof buf,
                  "%s: %.1f%% and %.1f%% of the overlapping %s lie in space the other %s saw as empty, seen from both "
                  "%ss (at most %.1f%% from both)",
                  w.test, 100.0 * out.violation_ratio, 100.0 * out.violation_ratio_lesser, w.samples, w.other, w.other,
                  100.0 * p.max_two_way_violation_ratio);
  } else if (out.occluded_ratio > p.max_occluded_ratio) {
    std::snprintf(buf, sizeof buf,
                  "%s: %.0f%% of the %s lie behind the other %s's surfaces (at most %.0f%%): the pose hides one %s "
                  "behind the other",
                  w.test, 100.0 * out.occluded_ratio, w.samples, w.other, 100.0 * p.max_occluded_ratio, w.other);
  } else {
    out.passed = true;
    return;
  }
  out.reason = buf;
  out.free_space_refused = true;
}

}  // namespace gasp::detail
