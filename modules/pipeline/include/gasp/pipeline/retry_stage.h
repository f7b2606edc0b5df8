#pragma once
/// \file retry_stage.h The pair pipeline's outer stage: what is tried again when a chain gives no
/// estimate. Two fallbacks, each a wider hypothesis set whose poses face the certificate's
/// stricter fallback limit (CertifyParams::fallback_max_violation_ratio):
/// 1. One-way partners: when the mutual associations give no verified hypothesis, the hypothesis
///    stage runs again with each patch's one-way best partner added (more right associations at
///    wide baselines, more wrong ones too).
/// 2. Finer scale: when the chain at the views' own scale gives no estimate, and not because a
///    view or the patch problem is degenerate (no scale fixes that; a dense problem that was
///    unobservable at a pose from a few wrong inliers says less and is retried), both depth images
///    are segmented again with their own parameters at finer_area_factor times their patch area,
///    and the whole chain runs once more on the mutual associations only. A small overlap holds
///    too few patches of the default size for a consensus; smaller patches give it more. The
///    count thresholds (RANSAC's min_inliers, the guided min_support) are not scaled: at a
///    smaller area they ask for less surface.
namespace gasp {

struct RetryParams {
  bool one_way_fallback = true;
  /// 0 = no finer-scale retry; else in [0.01, 1). 0.3 gives 12 cm^2 patches for the default
  /// 40 cm^2; views without depth are not retried.
  double finer_area_factor = 0.3;
};

/// Throws gasp::Error naming the first invalid parameter.
void validate(const RetryParams& params);

}  // namespace gasp
