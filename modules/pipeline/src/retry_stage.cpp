#include "gasp/pipeline/retry_stage.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

#include "gasp/core/error.h"
#include "retry_policy.h"

namespace gasp {

void validate(const RetryParams& p) {
  if (!(p.finer_area_factor == 0.0 || (p.finer_area_factor >= 0.01 && p.finer_area_factor < 1.0)))
    throw Error("retry: finer_area_factor must be 0 (off) or in [0.01, 1)");
}

namespace detail {

namespace {

/// The hypothesis's associations move into the result (the caller needs only its verdict and
/// guided associations afterwards).
void take(Hypothesis& h, PairResult& r) {
  r.used = std::move(h.used);
  r.correspondences = std::move(h.correspondences);
  r.pose = h.pose;
  if (h.guided_support >= 0) r.guided_support = h.guided_support;
  r.timings.ransac_ms += h.ransac_ms;
  r.timings.refine_ms += h.refine_ms;
  r.timings.guided_ms += h.guided_ms;
}

}  // namespace

Hypothesis hypothesiseWithFallback(const AssociatedViews& a, const HypothesiseParams& params, bool one_way,
                                   PairResult& r) {
  const auto& mutual = a.result.associations;
  Hypothesis h;
  if (!mutual.empty()) {
    h = hypothesise(a, mutual, params);
    take(h, r);
    if (h.verified) return h;
  } else {
    r.pose.reason = "no mutual associations";
  }
  if (!one_way || a.result.one_way.empty()) return h;
  const std::string mutual_reason = r.pose.reason;
  std::vector<PatchAssociation> wider = mutual;
  wider.insert(wider.end(), a.result.one_way.begin(), a.result.one_way.end());
  std::sort(wider.begin(), wider.end(), [](const PatchAssociation& x, const PatchAssociation& y) { return x.a < y.a; });
  h = hypothesise(a, std::move(wider), params);
  take(h, r);
  r.used_one_way = true;
  if (!h.verified) r.pose.reason = "mutual associations: " + mutual_reason + "; with one-way partners: " + r.pose.reason;
  return h;
}

bool finerScaleRetryApplies(const PairResult& r, const DepthView& source, const DepthView& target) {
  // A view's own geometry that leaves directions free is no better at a finer scale; a partial
  // pose from the dense rounds may become a full one there (smaller patches pair up where the
  // default ones did not).
  const bool degenerate = (r.pose.degenerate && !r.dense_unobservable) || r.views_free_directions > 0;
  return !r.pose.success && !degenerate && !source.depth_m.empty() && !target.depth_m.empty();
}

DepthView finerScaleView(const DepthView& view, double area_factor) {
  SuperpixelParams sp = view.superpixels;
  sp.target_patch_area_m2 *= area_factor;
  DepthView finer = makeDepthView(view.depth_m, view.projection, sp);
  finer.returns = view.returns;
  return finer;
}

std::string finerScaleReason(double area_factor, const std::string& reason) {
  char factor[32];
  std::snprintf(factor, sizeof factor, "%g", area_factor);
  return std::string("at ") + factor + "x the patch area: " + reason;
}

}  // namespace detail
}  // namespace gasp
