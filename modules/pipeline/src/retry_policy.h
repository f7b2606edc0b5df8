#pragma once
// The retry stage's policies (gasp/pipeline/retry_stage.h), for the orchestrator
// (pair_registration.cpp): the one-way fallback around the hypothesis stage, and the pieces of
// the finer-scale retry.
#include <string>

#include "gasp/pipeline/hypothesise_stage.h"
#include "gasp/pipeline/pair_registration.h"

namespace gasp::detail {

/// The hypothesis stage on the mutual associations; when they give no verified hypothesis and
/// `one_way` allows, again on the mutual and one-way associations together (r.used_one_way).
/// Fills r's hypothesis fields (used, correspondences, pose, guided_support, timings); the
/// returned hypothesis is the last one tried.
Hypothesis hypothesiseWithFallback(const AssociatedViews& a, const HypothesiseParams& params, bool one_way,
                                   PairResult& r);

/// Whether a result at the views' own scale may still become an estimate at a finer scale.
bool finerScaleRetryApplies(const PairResult& r, const DepthView& source, const DepthView& target);
/// `view` segmented again with its own parameters at area_factor times their patch area (throws
/// gasp::Error for a depth image that does not match its intrinsics).
DepthView finerScaleView(const DepthView& view, double area_factor);
/// "at 0.3x the patch area: " + reason.
std::string finerScaleReason(double area_factor, const std::string& reason);

}  // namespace gasp::detail
